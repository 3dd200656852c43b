#pragma once
// Explicit integration (semi-implicit Euler, midpoint, RK4) as a method of
// the registry.
#include "solver/method.hpp"

namespace atssim::solver::explicit_rk {

extern const MethodDescription kDescription;

}  // namespace atssim::solver::explicit_rk
