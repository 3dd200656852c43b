#include "solver/jpgd/jpgd_plan.hpp"
#include "solver/method.hpp"
#include "solver/vertex/stiffness_ratio.hpp"

namespace atssim::solver::jpgd {

namespace {

// springs: tet-edge springs in the stretch set (model/tet_builder.cpp).
constexpr scene::SolidModel kSolids[] = {scene::SolidModel::neo_hookean, scene::SolidModel::stvk,
                                         scene::SolidModel::springs};

// vertex_batches by default: the same bits as vertices, and 1.4-1.9x as
// fast on one sub-device, the whole device and two sub-devices at 64x64,
// 128x128 and 256x256 (docs/benchmarks.md, "JPGD in float8 lanes").
constexpr MethodOption kOptions[] = {
    {"chebyshev_rho",
     0.9,
     0.0,
     0.999,
     false,
     false,
     "a spectral radius 0 ≤ rho < 1 (0 = no acceleration; default 0.9, 0 on stiff scenes; jpgd)",
     {},
     true},
    {"jacobi_step", 0.5, 0.0, 1.0, true, false, "a step length 0 < step ≤ 1 (jpgd)"},
    {"momentum", 0.0, 0.0, 0.999, false, false, "a momentum 0 ≤ beta < 1 (0 = off, Chebyshev instead; jpgd)"},
    {"ordering", 1.0, 0.0, 3.0, false, false,
     "vertices or vertex_batches: one work-item per vertex, or per 8 consecutive vertices whose element sums run as 8 "
     "float lanes (the same bits; colors and color_batches mean the same; jpgd; default vertex_batches)",
     vertex::kJacobiOrderings, false, -1},
};

plan::SubstepPlan build(const SimLayout& layout, const MethodSettings& s) {
  // Chebyshev acceleration diverges on stiff scenes (vertex/stiffness_ratio.hpp).
  // Surface contact switches pairs on and off between iterations, which its
  // momentum keeps doing: `converge` on two layers stalled at y = 0.03 (rho
  // 0.9) and 0.02 (0.8) from k = 32 on; 0.7 reaches 2e-6 at k = 256.
  const double plain = layout.self_contact.enabled ? 0.7 : 0.9;
  const double rho = s.option_or("chebyshev_rho", vertex::stiff_for_jacobi(layout, s.substep_dt) ? 0.0 : plain);
  return make_jpgd_plan(layout, {s.substep_dt, s.iterations, rho, s.option("jacobi_step"), s.option("momentum"),
                                 vertex::jacobi_ordering(s.option("ordering"))});
}

}  // namespace

// The registry's line for jpgd (solver/method_registry.cpp).
extern const MethodDescription kDescription{
    .name = "jpgd",
    .summary = "block-Jacobi preconditioned gradient descent with Chebyshev or heavy-ball acceleration (Wang 2015)",
    .program = kProgram,
    .descent = true,
    .options = kOptions,
    .solid_models = kSolids,
    .build = build};

}  // namespace atssim::solver::jpgd
