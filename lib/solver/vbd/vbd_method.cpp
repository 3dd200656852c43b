#include "solver/method.hpp"
#include "solver/vbd/vbd_plan.hpp"

namespace atssim::solver::vbd {

namespace {

constexpr plan::TaskKind kKinds[] = {kVertex};

// springs: tet-edge springs in the stretch set (model/tet_builder.cpp).
constexpr scene::SolidModel kSolids[] = {scene::SolidModel::neo_hookean, scene::SolidModel::stvk,
                                         scene::SolidModel::springs};

plan::SubstepPlan build(const SimLayout& layout, const MethodSettings& s) {
  return make_vbd_plan(layout, s.substep_dt, s.iterations);
}

}  // namespace

// The registry's line for vbd (solver/method_registry.cpp).
extern const MethodDescription kDescription{
    .name = "vbd",
    .summary =
        "vertex block descent: Gauss-Seidel over vertex colors, one 3x3 Newton step per vertex (Chen et al. 2024)",
    .program = kProgram,
    .kinds = kKinds,
    .gauss_seidel = true,
    .descent = true,
    .solid_models = kSolids,
    .build = build};

}  // namespace atssim::solver::vbd
