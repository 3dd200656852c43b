#pragma once
// Vertex Block Descent (Chen et al. 2024) as a substep plan: predict, then
// per iteration a Gauss-Seidel sweep over the vertex colors (one task per
// color, cut-able between devices: a color's vertices share no element),
// then the velocity update.
#include "plan/substep_plan.hpp"
#include "solver/layout/sim_layout.hpp"
#include "solver/vertex/vertex_plan.hpp"

namespace atssim::solver::vbd {

plan::SubstepPlan make_vbd_plan(const SimLayout& layout, double substep_dt, int iterations,
                                vertex::VertexBuffers* ids = nullptr);

}  // namespace atssim::solver::vbd
