#include "solver/vertex/stiffness_ratio.hpp"

#include <cmath>

#include "solver/explicit/stability_limit.hpp"

namespace atssim::solver::vertex {

double stiffness_to_inertia(const SimLayout& layout, double substep_dt) {
  return substep_dt * substep_dt * explicit_rk::largest_eigenvalue_bound(layout);
}

bool stiff_for_jacobi(const SimLayout& layout, double substep_dt) {
  const double ratio = stiffness_to_inertia(layout, substep_dt);
  return std::isfinite(ratio) && ratio > kStiffForJacobi;
}

}  // namespace atssim::solver::vertex
