#pragma once
// The XPBD substep as a task graph with kernel launches (paper Fig. 2):
// predict -> per iteration: stretch color blocks, then bending color blocks,
// then tetrahedron (StVK strain) color blocks, in Gauss-Seidel order ->
// update velocity. Only the element sets the model has produce tasks.
#include "model/model.hpp"
#include "plan/substep_plan.hpp"
#include "solver/layout/sim_layout.hpp"

namespace atssim::solver::xpbd {

struct XpbdSettings {
  double substep_dt = 1.0 / 960.0;
  int iterations = 8;
};

// Buffer ids inside an XPBD plan (those absent from the model are -1).
struct XpbdBuffers {
  plan::BufferId x = -1, v = -1, x_prev = -1, stretch = -1, stretch_lambda = -1, bend = -1, bend_lambda = -1;
  plan::BufferId tet = -1, tet_lambda = -1;
};

plan::SubstepPlan make_xpbd_plan(const SimLayout& layout, const XpbdSettings& settings, XpbdBuffers* ids = nullptr);

}  // namespace atssim::solver::xpbd
