#pragma once
// Coulomb coefficients in a scene: `friction: 0.3` (static and kinetic
// alike) or `friction: {static: 0.4, kinetic: 0.3}` (one alone sets both),
// each from 0 to 100. Shared by colliders and `contact:`.
#include "scene/yaml_reader.hpp"

namespace atssim::scene {

struct FrictionDesc {
  double static_coefficient = 0.0;   // mu_s
  double kinetic_coefficient = 0.0;  // mu_k
};

// Throws atssim::Error (input) naming the line of a bad coefficient.
FrictionDesc read_friction(const YamlReader& r);

}  // namespace atssim::scene
