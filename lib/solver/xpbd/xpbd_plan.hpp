#pragma once
// The XPBD substep as a task graph with kernel launches (paper Fig. 2):
// predict -> per iteration: stretch color blocks (or batches), then bending color blocks,
// then tetrahedron (StVK strain) color blocks, in Gauss-Seidel order ->
// update velocity. Only the element sets the model has produce tasks.
#include <string_view>

#include "model/model.hpp"
#include "plan/substep_plan.hpp"
#include "plan/task_kind.hpp"
#include "solver/layout/sim_layout.hpp"

namespace atssim::solver::xpbd {

// The embedded program its plans run: kernels/xpbd/xpbd.cl.
inline constexpr std::string_view kProgram = "xpbd";

// XPBD's task kinds: color blocks (or batch sweeps) of constraints, each kind
// a Gauss-Seidel chain.
inline constexpr plan::TaskKind kStretch{{"stretch", true, false, false}};  // distance constraints
inline constexpr plan::TaskKind kBend{{"bend", true, false, false}};        // bending constraints
inline constexpr plan::TaskKind kTet{{"tet", true, false, false}};          // tetrahedra (StVK strain)

// The order of the stretch, bending and tet constraints (solver.ordering):
// colors = one task per color block, the blocks one after another;
// batches = one task per element set sweeping NvCloth's simd batches
// (solver/xpbd/xpbd_batches), a one-device order (no part to cut);
// color_batches = the color order, each color block cut into batches of 8
// elements that run as float8 lanes, one task per block (cut like colors).
enum class XpbdOrdering { colors, color_batches, batches };  // solver.ordering's choices in order

struct XpbdSettings {
  double substep_dt = 1.0 / 960.0;
  int iterations = 8;
  XpbdOrdering ordering = XpbdOrdering::colors;
};

// Buffer ids inside an XPBD plan (those absent from the model are -1).
struct XpbdBuffers {
  plan::BufferId x = -1, v = -1, x_prev = -1, stretch = -1, stretch_lambda = -1, bend = -1, bend_lambda = -1;
  plan::BufferId tet = -1, tet_lambda = -1;
};

plan::SubstepPlan make_xpbd_plan(const SimLayout& layout, const XpbdSettings& settings, XpbdBuffers* ids = nullptr);

}  // namespace atssim::solver::xpbd
