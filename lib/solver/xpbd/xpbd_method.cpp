#include "solver/xpbd/xpbd_method.hpp"

#include "solver/xpbd/xpbd_plan.hpp"

namespace atssim::solver::xpbd {

namespace {

// The strain constraints (common/xpbd_tet.h) minimise the StVK energy only.
// springs: tet-edge springs in the stretch set (model/tet_builder.cpp).
constexpr scene::SolidModel kSolids[] = {scene::SolidModel::stvk, scene::SolidModel::springs};

plan::SubstepPlan build(const SimLayout& layout, const MethodSettings& s) {
  return make_xpbd_plan(layout, {s.substep_dt, s.iterations});
}

}  // namespace

const MethodDescription kDescription{
    "xpbd",  "extended position-based dynamics: Gauss-Seidel over constraint color blocks (Macklin et al. 2016)",
    true,    {},
    kSolids, build};

}  // namespace atssim::solver::xpbd
