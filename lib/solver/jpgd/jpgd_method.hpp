#pragma once
// The jpgd method's entry in the method registry (solver/method_registry.hpp).
#include "solver/method.hpp"

namespace atssim::solver::jpgd {

extern const MethodDescription kDescription;

}  // namespace atssim::solver::jpgd
