#pragma once
// Collision tasks every method appends (He et al. 2025 Fig. 2: collision
// constraints serialized at the end of an iteration): the ground plane, and
// the contact and friction tasks of the analytic colliders
// (kernels/common/contact_steps.cl). A scene without colliders gets no
// contact tasks.
#include "plan/substep_plan.hpp"
#include "solver/layout/sim_layout.hpp"

namespace atssim::solver {

// After `last`, a task that projects the particles of `positions` above the
// layout's ground plane; returns the new last task, or `last` when the
// layout has no ground. Its launch covers independent particles (cut-able).
sched::TaskId add_ground_task(plan::SubstepPlan& plan, sched::TaskId last, const SimLayout& layout,
                              plan::BufferId positions, int iteration);

// The buffers every task that takes the colliders reads.
struct ColliderBuffers {
  plan::BufferId records = -1;  // role colliders: the host rewrites it between substeps when colliders move
  plan::BufferId near = -1;     // per particle its near list of each mesh collider (common/mesh_near.h; cache)
};

// The layout's colliders as buffers; empty ones when the layout has none
// (the vertex kernels take them with a count of 0).
ColliderBuffers add_collider_buffers(plan::SubstepPlan& plan, const SimLayout& layout);

// A kernel's collider parameters: the records, their count, the near lists.
std::vector<plan::KernelArg> collider_args(const SimLayout& layout, const ColliderBuffers& colliders);
// `before`, the collider parameters, then `after`.
std::vector<plan::KernelArg> with_colliders(std::vector<plan::KernelArg> before, const SimLayout& layout,
                                            const ColliderBuffers& colliders,
                                            const std::vector<plan::KernelArg>& after = {});

// After `last` (predict), every particle's near lists of the mesh colliders
// kept or made at `positions` (colliders_near). Returns the new last task,
// or `last` when the layout has no mesh collider.
sched::TaskId add_collider_near_task(plan::SubstepPlan& plan, sched::TaskId last, const SimLayout& layout,
                                     const ColliderBuffers& colliders, plan::BufferId positions);

// After `last`, the contact task of iteration `iteration`: every particle of
// `positions` put back out of the colliders' thickened surfaces. Returns the
// new last task, or `last` when the layout has no colliders.
sched::TaskId add_contact_task(plan::SubstepPlan& plan, sched::TaskId last, const SimLayout& layout,
                               const ColliderBuffers& colliders, plan::BufferId positions, int iteration);

// After `last` (the iterations), Coulomb friction on the substep's
// displacement of every particle that touches a collider. Returns the new
// last task, or `last` when the layout has no colliders.
// `friction`: the buffer of add_friction_buffer.
sched::TaskId add_friction_task(plan::SubstepPlan& plan, sched::TaskId last, const SimLayout& layout,
                                const ColliderBuffers& colliders, plan::BufferId friction, plan::BufferId positions,
                                plan::BufferId start_positions, plan::BufferId velocities, double substep_dt);

// The particles' material friction (SimLayout::friction) as a buffer, for
// the friction tasks.
plan::BufferId add_friction_buffer(plan::SubstepPlan& plan, const SimLayout& layout);

}  // namespace atssim::solver
