#pragma once
// The vbd method's entry in the method registry (solver/method_registry.hpp).
#include "solver/method.hpp"

namespace atssim::solver::vbd {

extern const MethodDescription kDescription;

}  // namespace atssim::solver::vbd
