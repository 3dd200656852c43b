#pragma once
// A collider as the scene gives it (docs/scene-format.md, `colliders:`): a
// plane, sphere, capsule, box or triangle mesh the particles stay out of,
// with a contact thickness and Coulomb friction, static or kinematic. Plain
// data, validated.
#include <array>
#include <string>
#include <vector>

#include "scene/collider_motion.hpp"

namespace atssim::scene {

enum class ColliderShape { plane, sphere, capsule, box, mesh };

struct ColliderDesc {
  std::string name;
  ColliderShape shape = ColliderShape::plane;
  std::array<double, 3> point{0.0, 0.0, 0.0};       // plane: a point on it; sphere, box: centre; capsule: end a;
                                                    // mesh: position of its origin
  std::array<double, 3> normal{0.0, 1.0, 0.0};      // plane: normal (normalised when the model is built)
  std::array<double, 3> end{0.0, 0.0, 0.0};         // capsule: end b
  std::array<double, 3> size{1.0, 1.0, 1.0};        // box: full extents along its local axes
  std::array<double, 3> rotate_deg{0.0, 0.0, 0.0};  // box (rotate), mesh (rotation): about x, then y, then z
  double radius = 0.0;                              // sphere, capsule (> 0)
  double thickness = 0.005;                         // m (> 0): particles keep this distance from the surface
  double static_friction = 0.0;                     // Coulomb mu_s (>= 0)
  double kinetic_friction = 0.0;                    // Coulomb mu_k (>= 0)
  bool friction_set = false;                        // `friction:` given; else the touching object's material decides
  double stiffness = 100.0;                         // contact energy stiffness relative to m/h^2 (> 0)
  ColliderMotion motion;                            // still, velocity or keyframes
  // mesh: the file (resolved against the scene's folder), its scale per
  // axis and the triangles as loaded (welded, in the file's coordinates).
  std::string file;
  std::array<double, 3> scale{1.0, 1.0, 1.0};
  std::vector<std::array<double, 3>> mesh_vertices;
  std::vector<std::array<int, 3>> mesh_triangles;
  int source_line = 0;
};

}  // namespace atssim::scene
