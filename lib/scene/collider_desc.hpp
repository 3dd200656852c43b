#pragma once
// An analytic collider as the scene gives it (docs/scene-format.md,
// `colliders:`): a plane, sphere, capsule or box the particles stay out of,
// with a contact thickness and Coulomb friction. Plain data, validated.
#include <array>
#include <string>

namespace atssim::scene {

enum class ColliderShape { plane, sphere, capsule, box };

struct ColliderDesc {
  std::string name;
  ColliderShape shape = ColliderShape::plane;
  std::array<double, 3> point{0.0, 0.0, 0.0};       // plane: a point on it; sphere, box: centre; capsule: end a
  std::array<double, 3> normal{0.0, 1.0, 0.0};      // plane: normal (normalised when the model is built)
  std::array<double, 3> end{0.0, 0.0, 0.0};         // capsule: end b
  std::array<double, 3> size{1.0, 1.0, 1.0};        // box: full extents along its local axes
  std::array<double, 3> rotate_deg{0.0, 0.0, 0.0};  // box: about x, then y, then z
  double radius = 0.0;                              // sphere, capsule (> 0)
  double thickness = 0.005;                         // m (> 0): particles keep this distance from the surface
  double static_friction = 0.0;                     // Coulomb mu_s (>= 0)
  double kinetic_friction = 0.0;                    // Coulomb mu_k (>= 0)
  double stiffness = 100.0;                         // contact energy stiffness relative to m/h^2 (> 0)
  int source_line = 0;
};

}  // namespace atssim::scene
