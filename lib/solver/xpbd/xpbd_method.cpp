#include "solver/method.hpp"
#include "solver/xpbd/xpbd_plan.hpp"

namespace atssim::solver::xpbd {

namespace {

constexpr plan::TaskKind kKinds[] = {kStretch, kBend, kTet};

// The strain constraints (common/xpbd_tet.h) minimise the StVK energy only.
// springs: tet-edge springs in the stretch set (model/tet_builder.cpp).
constexpr scene::SolidModel kSolids[] = {scene::SolidModel::stvk, scene::SolidModel::springs};
constexpr std::string_view kOrderings[] = {"colors", "color_batches", "batches"};  // XpbdOrdering's values in order

// Unset, solver.ordering is color_batches from this many particles on and
// colors below: on the whole CPU device and on two sub-devices the lanes
// were 10-15 % slower than colors at 40x40 and 64x64 and 7-17 % faster at
// 128x128 (docs/benchmarks.md, "Colors or color_batches by size").
constexpr std::size_t kLanesFromParticles = 128 * 128;

constexpr MethodOption kOptions[] = {
    {"ordering", 0.0, 0.0, 2.0, false, false,
     "colors, color_batches or batches: the order of the stretch, bending and tet constraints, one task per color "
     "block, one task per color block cut into batches of 8 float lanes, or one sweep of NvCloth's simd batches "
     "per element set (xpbd; unset: color_batches from 16384 particles, colors below; batches: schedule single "
     "only)",
     kOrderings, true, 2},
};

plan::SubstepPlan build(const SimLayout& layout, const MethodSettings& s) {
  const double unset = layout.x.size() >= kLanesFromParticles ? 1.0 : 0.0;
  return make_xpbd_plan(layout, {s.substep_dt, s.iterations,
                                 static_cast<XpbdOrdering>(static_cast<int>(s.option_or("ordering", unset)))});
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
