#include "solver/method.hpp"
#include "solver/xpbd/xpbd_plan.hpp"

namespace atssim::solver::xpbd {

namespace {

constexpr plan::TaskKind kKinds[] = {kStretch, kBend, kTet};

// The strain constraints (common/xpbd_tet.h) minimise the StVK energy only.
// springs: tet-edge springs in the stretch set (model/tet_builder.cpp).
constexpr scene::SolidModel kSolids[] = {scene::SolidModel::stvk, scene::SolidModel::springs};
constexpr std::string_view kOrderings[] = {"colors", "color_batches", "batches"};  // XpbdOrdering's values in order

constexpr MethodOption kOptions[] = {
    {"ordering", 0.0, 0.0, 2.0, false, false,
     "colors, color_batches or batches: the order of the stretch, bending and tet constraints, one task per color "
     "block, one task per color block cut into batches of 8 float lanes, or one sweep of NvCloth's simd batches "
     "per element set (xpbd; batches: schedule single only)",
     kOrderings, false, 2},
};

plan::SubstepPlan build(const SimLayout& layout, const MethodSettings& s) {
  return make_xpbd_plan(
      layout, {s.substep_dt, s.iterations, static_cast<XpbdOrdering>(static_cast<int>(s.option("ordering")))});
}

}  // namespace

// The registry's line for xpbd (solver/method_registry.cpp).
extern const MethodDescription kDescription{
    .name = "xpbd",
    .summary = "extended position-based dynamics: Gauss-Seidel over constraint color blocks (Macklin et al. 2016)",
    .program = kProgram,
    .kinds = kKinds,
    .gauss_seidel = true,
    .options = kOptions,
    .solid_models = kSolids,
    .build = build};

}  // namespace atssim::solver::xpbd
