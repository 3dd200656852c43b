#include "solver/jpgd/jpgd_method.hpp"

#include "solver/jpgd/jpgd_plan.hpp"
#include "solver/vertex/stiffness_ratio.hpp"

namespace atssim::solver::jpgd {

namespace {

// springs: tet-edge springs in the stretch set (model/tet_builder.cpp).
constexpr scene::SolidModel kSolids[] = {scene::SolidModel::neo_hookean, scene::SolidModel::stvk,
                                         scene::SolidModel::springs};

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
};

plan::SubstepPlan build(const SimLayout& layout, const MethodSettings& s) {
  // Chebyshev acceleration diverges on stiff scenes (vertex/stiffness_ratio.hpp).
  const double rho = s.option_or("chebyshev_rho", vertex::stiff_for_jacobi(layout, s.substep_dt) ? 0.0 : 0.9);
  return make_jpgd_plan(layout, {s.substep_dt, s.iterations, rho, s.option("jacobi_step"), s.option("momentum")});
}

}  // namespace

const MethodDescription kDescription{
    "jpgd",  "block-Jacobi preconditioned gradient descent with Chebyshev or heavy-ball acceleration (Wang 2015)",
    false,   kOptions,
    kSolids, build};

}  // namespace atssim::solver::jpgd
