#include "solver/energy/finite_stiffness.hpp"

#include <cmath>

#include <fmt/format.h>

#include "util/error.hpp"

namespace atssim::solver::energy {

namespace {

template <typename Constraint>
void check(const std::vector<Constraint>& constraints, const char* kind) {
  for (std::size_t i = 0; i < constraints.size(); ++i) {
    const float compliance = constraints[i].compliance;
    if (compliance > 0.0f) continue;
    // The layout has no scene lines: the caller that has them names the one
    // that set the compliance (Setting::compliance, app/scene_checks).
    std::string message = fmt::format(
        "{} constraint {} has compliance {} (infinitely stiff): its energy is undefined, and converging to the "
        "energy minimum needs finite stiffness; give the material a finite {}_stiffness",
        kind, i, compliance, kind);
    throw Error(message, Setting::compliance, message);
  }
}

}  // namespace

void require_finite_stiffness(const SimLayout& layout) {
  check(layout.stretch, "stretch");
  check(layout.bend, "bend");
}

void require_valid_tets(const SimLayout& layout) {
  for (std::size_t i = 0; i < layout.tets.size(); ++i) {
    const ats_tet_c& t = layout.tets[i];
    // Negated comparisons so that NaN fails them too.
    if (!(t.mu > 0.0f && std::isfinite(t.mu)) || !(t.lambda >= 0.0f && std::isfinite(t.lambda))) {
      throw input_error(fmt::format(
          "tetrahedron {} has Lame parameters mu = {}, lambda = {}: the elastic energy needs mu > 0 and lambda >= 0; "
          "give the solid a youngs_modulus > 0 and a poisson_ratio in [0, 0.5)",
          i, t.mu, t.lambda));
    }
    if (!(t.volume > 0.0f && std::isfinite(t.volume))) {
      throw input_error(fmt::format("tetrahedron {} has rest volume {}: it needs a positive volume", i, t.volume));
    }
    if (t.model != ATS_TET_NEO_HOOKEAN && t.model != ATS_TET_STVK) {
      throw input_error(
          fmt::format("tetrahedron {} has energy model {}: known are {} (stable neo-Hookean) and {} (StVK)", i, t.model,
                      ATS_TET_NEO_HOOKEAN, ATS_TET_STVK));
    }
  }
}

}  // namespace atssim::solver::energy
