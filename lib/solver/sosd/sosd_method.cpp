#include "solver/method.hpp"
#include "solver/sosd/sosd_plan.hpp"
#include "solver/vertex/stiffness_ratio.hpp"

namespace atssim::solver::sosd {

namespace {

constexpr plan::TaskKind kKinds[] = {kSystems, kMainBlock, kStencils, kCombine};

// springs: tet-edge springs in the stretch set (model/tet_builder.cpp).
constexpr scene::SolidModel kSolids[] = {scene::SolidModel::neo_hookean, scene::SolidModel::stvk,
                                         scene::SolidModel::springs};

constexpr std::string_view kOrderings[] = {"colors", "color_batches"};  // SosdOrdering's values in order

// color_batches by default: the same bits as colors, and 1.35-1.50x as fast
// on the whole device, split and heft at 64x64 to 256x256 (docs/benchmarks.md,
// "SOSD's stencil solve unrolled, and its bending stencils in lanes").

constexpr MethodOption kOptions[] = {
    {"stencil_step",
     0.7,
     0.0,
     1.0,
     true,
     false,
     "a step length 0 < step ≤ 1 (default 0.7, 0.35 on stiff scenes; sosd)",
     {},
     true},
    {"ordering", 1.0, 0.0, 1.0, false, false,
     "colors or color_batches: one work-item per stencil, or per 8 bending stencils of a color whose Cholesky solves "
     "run as 8 float lanes (the same bits; sosd; default color_batches)",
     kOrderings, false, -1},
};

plan::SubstepPlan build(const SimLayout& layout, const MethodSettings& s) {
  // A long stencil step diverges on stiff scenes (vertex/stiffness_ratio.hpp).
  const double step = s.option_or("stencil_step", vertex::stiff_for_jacobi(layout, s.substep_dt) ? 0.35 : 0.7);
  return make_sosd_plan(layout, s.substep_dt, s.iterations, step, nullptr,
                        static_cast<SosdOrdering>(static_cast<int>(s.option("ordering"))));
}

}  // namespace

// Hybrid: its Gauss-Seidel part is the main block's precedence in one
// combine step per iteration; its stencil solves are Jacobi sweeps.
// The registry's line for sosd (solver/method_registry.cpp).
extern const MethodDescription kDescription{
    .name = "sosd",
    .summary = "second-order stencil descent: per-element Newton solves, Jacobi across stencils (Lan et al. 2023)",
    .program = kProgram,
    .kinds = kKinds,
    .descent = true,
    .options = kOptions,
    .solid_models = kSolids,
    .build = build};

}  // namespace atssim::solver::sosd
