#pragma once
// The parts every vertex-block method's substep shares: buffers (state,
// inertia target, elements, per-vertex element lists), predict, and the
// velocity update; VBD and JPGD put their iterations in between.
#include "plan/substep_plan.hpp"
#include "solver/collision_tasks.hpp"
#include "solver/layout/sim_layout.hpp"
#include "solver/vertex/vertex_layout.hpp"

namespace atssim::solver::vertex {

struct VertexBuffers {
  plan::BufferId x = -1, v = -1, x_prev = -1, x_tilde = -1, stretch = -1, bend = -1, tets = -1, adjacency_offsets = -1,
                 adjacency = -1, order = -1, friction = -1;
  ColliderBuffers colliders;
};

// Adds the buffers, the predict task and the colliders' near lists after
// it; returns the last of them. Throws
// atssim::Error (input) when a constraint is infinitely stiff (compliance
// 0): these methods minimise an energy, which then does not exist.
sched::TaskId begin_vertex_plan(plan::SubstepPlan& plan, const SimLayout& layout, const VertexLayout& vertices,
                                double substep_dt, VertexBuffers& ids);

// Adds the friction task (when the layout has colliders) and the velocity
// update after `last`.
void end_vertex_plan(plan::SubstepPlan& plan, const SimLayout& layout, sched::TaskId last, const VertexBuffers& ids,
                     double substep_dt);

// The collider arguments of a vertex kernel: the records, the count, the
// near lists.
std::vector<plan::KernelArg> collider_args(const SimLayout& layout, const VertexBuffers& ids);

// The spring-damping arguments of a vertex kernel (common/vertex_system.h,
// add_spring_damping): the start positions and 1/h, or 0 when no spring of
// the layout is damped (the kernels then skip the term).
std::vector<plan::KernelArg> damping_args(const SimLayout& layout, const VertexBuffers& ids, double substep_dt);

}  // namespace atssim::solver::vertex
