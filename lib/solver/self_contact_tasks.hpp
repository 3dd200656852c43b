#pragma once
// The tasks of contact between simulated surfaces (scene `contact: {self:
// true}`; kernels/contact/self_contact.cl), which every method's plan
// builder adds with a call or two: detection at the start of the substep
// on x_t (BVH refit, the three pair queries, the per-vertex displacement
// bound), the bound on the first guess, and per method either the contact
// energy inside its vertex solves (VBD, JPGD, SOSD: the kernel arguments
// below) or XPBD's inequality constraints after each iteration. A layout
// without self contact gets no tasks and empty buffers (the vertex kernels
// then take sc_on = 0).
#include <vector>

#include "plan/substep_plan.hpp"
#include "solver/collision_tasks.hpp"
#include "solver/layout/sim_layout.hpp"

namespace atssim::solver {

struct SelfContactBuffers {
  plan::BufferId tris = -1, edges = -1, leaves = -1, nodes = -1, levels = -1, incidence = -1, vt = -1, tv = -1, ee = -1,
                 bound = -1, x_out = -1,  // x_out: friction's scratch copy
      motion = -1,  // per block of leaves the boxes of x_t, of the displacements since x_det and of the predicted steps
      corner_start = -1, corners = -1,  // per block of leaves its triangles' corners, each once (CSR)
      clusters = -1,                    // per cluster of blocks the box of their x_t boxes
      x_det = -1, state = -1,  // where the blocks last took stock; the lists' state (common/self_contact_lists.h)
      block_rho0 = -1, block_rho = -1,                 // per block of leaves its rho at x_det and in this substep
      block_make = -1,                                 // per block whether it makes its lists in this substep
      vertex_block = -1, edge_block = -1,              // per vertex and edge the block of the leaf that owns it
      vt_d = -1, tv_d = -1, ee_d = -1,                 // the listed pairs' distances at x_t
      vt_reach = -1, tv_reach = -1, ee_reach = -1,     // per list the nearest its primitive can be (sc_store_distances)
      vt_listed = -1, tv_listed = -1, ee_listed = -1,  // per list its count, packed when the lists are made
      tv_count = -1, ee_count = -1, vt_count = -1,     // per list its near entries' count, packed (sc_near_vertex)
      vt_total = -1,                                   // per vertex the near entries it is in, packed
      vt_near = -1, tv_near = -1, ee_near = -1,        // the entries that can come within the thickness this substep
      vt_l = -1, tv_l = -1,
                 ee_l = -1,  // per near-list entry the pair's normal, multiplier and weights (XPBD), or friction
      vt_k = -1, tv_k = -1, ee_k = -1,  // per list the count of its active entries (the projection, then friction)
      moved = -1,                       // per vertex how far it is from x_t (the near entries' skip, sc_still_apart)
      moved_blocks = -1, most = -1;     // the largest `moved` per block of vertices, then of all (sc_list_apart)
  ColliderBuffers colliders;  // the layout's colliders, which every clamp to the bound puts the positions back out of
};

// `colliders`: the plan's collider buffers (solver/collision_tasks
// add_collider_buffers), or none (records -1).
SelfContactBuffers add_self_contact_buffers(plan::SubstepPlan& plan, const SimLayout& layout,
                                            const ColliderBuffers& colliders);

// After `last` (predict): detection on `start` (x_t), then `positions` (the
// first guess) held within each vertex's bound of x_t. Returns the new last
// task, or `last` when the layout has no self contact.
sched::TaskId add_self_contact_detection(plan::SubstepPlan& plan, sched::TaskId last, const SimLayout& layout,
                                         const SelfContactBuffers& b, plan::BufferId start, plan::BufferId positions);

// A vertex kernel's self-contact parameters: tris, edges, incidence, the
// near lists (vt, tv, ee), bound, n, k (for the inertia step `inertia_h`), r, on. They follow
// the kernel's x_start and inv_h (vertex::damping_args), which the bound and
// the damping share.
std::vector<plan::KernelArg> self_contact_args(const SimLayout& layout, const SelfContactBuffers& b, double inertia_h);

// After `last`: `positions` held within each vertex's bound of `start`
// and put back out of the colliders (JPGD and SOSD after each iteration;
// XPBD before its projection, which passes `moved` to have each vertex's
// distance from `start` measured in the same pass, and whose iteration
// ends with the colliders' task: no colliders then). Returns the new last
// task, or `last`.
sched::TaskId add_self_contact_clamp(plan::SubstepPlan& plan, sched::TaskId last, const SimLayout& layout,
                                     const SelfContactBuffers& b, plan::BufferId start, plan::BufferId positions,
                                     int iteration, plan::BufferId moved = -1);

// XPBD: the per-entry buffers add_self_contact_projection needs (into b).
void add_self_contact_projection_buffers(plan::SubstepPlan& plan, const SimLayout& layout, SelfContactBuffers& b);

// XPBD, after `last`: the positions held within the bound, then every
// pair's inequality constraint, per list entry, then per vertex (Jacobi).
// Returns the new last task, or `last`.
sched::TaskId add_self_contact_projection(plan::SubstepPlan& plan, sched::TaskId last, const SimLayout& layout,
                                          const SelfContactBuffers& b, plan::BufferId start, plan::BufferId positions,
                                          int iteration);

// After the iterations, every method: Coulomb friction between the surfaces
// in contact (scene `contact.friction`) from `positions` into a scratch
// copy, then back within the bound; `start` and `velocities` (with the
// substep's gravity, after predict) give the inertial prediction
// start + h velocities. Returns the new last task, or `last` when the layout
// has no self contact or no friction.
sched::TaskId add_self_contact_friction(plan::SubstepPlan& plan, sched::TaskId last, const SimLayout& layout,
                                        SelfContactBuffers& b, plan::BufferId start, plan::BufferId positions,
                                        plan::BufferId velocities, plan::BufferId friction, double h);

}  // namespace atssim::solver
