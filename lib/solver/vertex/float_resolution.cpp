#include "solver/vertex/float_resolution.hpp"

#include <cmath>

#include <fmt/format.h>

#include "solver/explicit/stability_limit.hpp"
#include "util/error.hpp"

namespace atssim::solver::vertex {

double stiffness_to_inertia(const SimLayout& layout, double substep_dt) {
  return substep_dt * substep_dt * explicit_rk::largest_eigenvalue_bound(layout);
}

void require_resolvable_inertia(const SimLayout& layout, double substep_dt, int substeps, std::string_view method) {
  const double ratio = stiffness_to_inertia(layout, substep_dt);
  // An infinite stiffness (zero compliance) is refused by the method with its scene line.
  if (!std::isfinite(ratio) || !(ratio > kMaxStiffnessToInertia)) return;
  const double needed = std::ceil(substeps * std::sqrt(ratio / kMaxStiffnessToInertia));
  throw input_error(fmt::format(
      "solver.method {}: the stiffness is {:.2g} times the inertia m/h² (h² λmax(M⁻¹K)), beyond the {:.0e} that "
      "float32 vertex solves resolve: gravity and momentum vanish in rounding; raise the density, lower the "
      "stiffness, use simulation.substeps ≥ {:.0f}, or solver.method xpbd",
      method, ratio, kMaxStiffnessToInertia, needed));
}

}  // namespace atssim::solver::vertex
