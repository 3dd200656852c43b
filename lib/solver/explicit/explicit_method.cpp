#include "solver/explicit/explicit_plan.hpp"
#include "solver/explicit/stability_limit.hpp"
#include "solver/method.hpp"

namespace atssim::solver::explicit_rk {

namespace {

constexpr scene::SolidModel kSolids[] = {scene::SolidModel::neo_hookean, scene::SolidModel::stvk,
                                         scene::SolidModel::springs};
constexpr std::string_view kNoYes[] = {"false", "true"};

constexpr MethodOption kOptions[] = {
    {"integrator", 0.0, 0.0, 2.0, false, false, "semi_euler, midpoint or rk4 (explicit)", kIntegratorNames},
    {"allow_unstable", 0.0, 0.0, 1.0, false, false,
     "true or false: run a substep above the estimated stable step (explicit)", kNoYes},
};

plan::SubstepPlan build(const SimLayout& layout, const MethodSettings& s) {
  const auto integrator = static_cast<Integrator>(static_cast<int>(s.option("integrator")));
  if (s.option("allow_unstable") == 0.0) require_stable_step(layout, integrator, s.substep_dt, s.substeps);
  return make_explicit_plan(layout, {s.substep_dt, integrator});
}

}  // namespace

// The registry's line for explicit (solver/method_registry.cpp).
extern const MethodDescription kDescription{
    .name = "explicit",
    .summary = "explicit integration of the elastic forces: semi-implicit Euler, midpoint or RK4 (seed 001 Eqs. 2-4)",
    .program = kProgram,
    .implicit = false,
    .options = kOptions,
    .solid_models = kSolids,
    .build = build,
    .colliders = false};  // no contact tasks yet: a scene with colliders is refused

}  // namespace atssim::solver::explicit_rk
