#pragma once
// The sosd method's entry in the method registry (solver/method_registry.hpp).
#include "solver/method.hpp"

namespace atssim::solver::sosd {

extern const MethodDescription kDescription;

}  // namespace atssim::solver::sosd
