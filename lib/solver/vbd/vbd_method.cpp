#include "solver/method.hpp"
#include "solver/vbd/vbd_plan.hpp"

namespace atssim::solver::vbd {

namespace {

constexpr plan::TaskKind kKinds[] = {kVertex};

// springs: tet-edge springs in the stretch set (model/tet_builder.cpp).
constexpr scene::SolidModel kSolids[] = {scene::SolidModel::neo_hookean, scene::SolidModel::stvk,
                                         scene::SolidModel::springs};

constexpr std::string_view kOrderings[] = {"colors", "color_batches"};  // VbdOrdering's values in order

// color_batches by default: the same bits as colors, and on one sub-device,
// the whole device and two sub-devices 1.8-2.0x as fast at 64x64, 128x128
// and 256x256 (docs/benchmarks.md, "VBD in float8 lanes").
constexpr MethodOption kOptions[] = {
    {"ordering", 1.0, 0.0, 1.0, false, false,
     "colors or color_batches: one work-item per vertex of a color, or per batch of 8 vertices of a color whose "
     "element sums run as 8 float lanes (the same bits; vbd; default color_batches)",
     kOrderings, false, -1},
};

plan::SubstepPlan build(const SimLayout& layout, const MethodSettings& s) {
  return make_vbd_plan(layout, s.substep_dt, s.iterations, nullptr,
                       static_cast<VbdOrdering>(static_cast<int>(s.option_or("ordering", 1.0))));
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
    .options = kOptions,
    .solid_models = kSolids,
    .build = build};

}  // namespace atssim::solver::vbd
