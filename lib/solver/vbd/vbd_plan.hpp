#pragma once
// Vertex Block Descent (Chen et al. 2024) as a substep plan: predict, then
// per iteration a Gauss-Seidel sweep over the vertex colors (one task per
// color, cut-able between devices: a color's vertices share no element),
// then the velocity update.
#include <string_view>

#include "plan/substep_plan.hpp"
#include "plan/task_kind.hpp"
#include "solver/layout/sim_layout.hpp"
#include "solver/vertex/vertex_plan.hpp"

namespace atssim::solver::vbd {

// The embedded program its plans run: kernels/vbd/vbd.cl.
inline constexpr std::string_view kProgram = "vbd";

// VBD's task kind: one vertex color's block-descent steps, a Gauss-Seidel
// chain over the colors.
inline constexpr plan::TaskKind kVertex{{"vertex", true, false, true}};

// solver.ordering: colors runs a task per color, a work-item per vertex;
// color_batches a task per color, a work-item per batch of 8 vertices whose
// gather runs as float lanes (kernels/common/vertex_system_lanes.h): the same
// bits.
enum class VbdOrdering { colors, color_batches };  // solver.ordering's choices in order

plan::SubstepPlan make_vbd_plan(const SimLayout& layout, double substep_dt, int iterations,
                                vertex::VertexBuffers* ids = nullptr, VbdOrdering ordering = VbdOrdering::colors);

}  // namespace atssim::solver::vbd
