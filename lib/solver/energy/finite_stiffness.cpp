#include "solver/energy/finite_stiffness.hpp"

#include <fmt/format.h>

#include "util/error.hpp"

namespace atssim::solver::energy {

namespace {

template <typename Constraint>
void check(const std::vector<Constraint>& constraints, const char* kind) {
  for (std::size_t i = 0; i < constraints.size(); ++i) {
    const float compliance = constraints[i].compliance;
    if (compliance > 0.0f) continue;
    throw input_error(fmt::format(
        "{} constraint {} has compliance {} (infinitely stiff): its energy is undefined, and converging to the "
        "energy minimum needs finite stiffness; give the material a finite {}_stiffness",
        kind, i, compliance, kind));
  }
}

}  // namespace

void require_finite_stiffness(const xpbd::XpbdLayout& layout) {
  check(layout.stretch, "stretch");
  check(layout.bend, "bend");
}

}  // namespace atssim::solver::energy
