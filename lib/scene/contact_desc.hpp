#pragma once
// Contact between the simulated objects themselves (docs/scene-format.md,
// `contact:`): vertex-triangle and edge-edge proximity within a thickness
// over every object's surface, so cloth-cloth, self-collision and
// cloth-solid. Off unless the scene asks for it. Plain data, validated.
#include <string>

namespace atssim::scene {

struct SelfContactDesc {
  bool enabled = false;           // `self: true`
  double thickness = 0.005;       // m (> 0): surfaces keep this distance apart
  double stiffness = 100.0;       // contact energy stiffness relative to m/h² (> 0), m the mean surface particle mass
  double query_radius = 0.0;      // m: detection radius (≥ thickness); 0 = 3 × thickness
  double static_friction = 0.0;   // Coulomb mu_s between the surfaces (>= 0)
  double kinetic_friction = 0.0;  // Coulomb mu_k
  bool strict = false;            // `strict: true`: a frame whose surfaces crossed ends the run (exit 1)
  std::string where;              // "file:line" of `contact:` (for errors found when the model is built)
};

}  // namespace atssim::scene
