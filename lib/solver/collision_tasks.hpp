#pragma once
// Collision tasks every method appends at the end of an iteration (He et al.
// 2025 Fig. 2: collision constraints serialized at the end of an iteration).
// This version has one collider, a ground plane.
#include "plan/substep_plan.hpp"
#include "solver/layout/sim_layout.hpp"

namespace atssim::solver {

// After `last`, a task that projects the particles of `positions` above the
// layout's ground plane; returns the new last task, or `last` when the
// layout has no ground. Its launch covers independent particles (cut-able).
sched::TaskId add_ground_task(plan::SubstepPlan& plan, sched::TaskId last, const SimLayout& layout,
                              plan::BufferId positions, int iteration);

}  // namespace atssim::solver
