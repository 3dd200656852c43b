#pragma once
// The xpbd method's entry in the method registry (solver/method_registry.hpp).
#include "solver/method.hpp"

namespace atssim::solver::xpbd {

extern const MethodDescription kDescription;

}  // namespace atssim::solver::xpbd
