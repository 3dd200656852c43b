#include "solver/collision_tasks.hpp"

#include <fmt/format.h>

#include "common/mesh_near.h"
#include "solver/layout/particle_tables.hpp"

namespace atssim::solver {

using Arg = plan::KernelArg;

sched::TaskId add_ground_task(plan::SubstepPlan& plan, sched::TaskId last, const SimLayout& layout,
                              plan::BufferId positions, int iteration) {
  if (!layout.has_ground) return last;
  const int n = static_cast<int>(layout.x.size());
  return plan.add_task_after(
      last,
      plan::make_task(fmt::format("it{}/collision/ground", iteration + 1), plan::TaskKind::collision, iteration, 0),
      {"particles_ground",
       {0, n},
       {Arg::of_buffer(positions), Arg::of_float(layout.ground_y)},
       {particle_write(positions)}});
}

namespace {

// How many near lists a particle has: one per mesh collider.
int near_slots(const SimLayout& layout) {
  return layout.collider_count > 0 ? static_cast<int>(layout.colliders.front().near_slots) : 0;
}

}  // namespace

ColliderBuffers add_collider_buffers(plan::SubstepPlan& plan, const SimLayout& layout) {
  ColliderBuffers b;
  b.records = plan.add_buffer("colliders", plan::BufferRole::colliders, plan::bytes_of(layout.colliders));
  // Zeros: no list (margin 0); the lists check themselves, so a stale or
  // missing one costs a walk, never a different result (common/mesh_near.h).
  const std::size_t lists = layout.x.size() * static_cast<std::size_t>(near_slots(layout));
  b.near =
      plan.add_buffer("collider_near", plan::BufferRole::cache, std::vector<std::byte>(lists * sizeof(ats_mesh_near)));
  return b;
}

std::vector<plan::KernelArg> collider_args(const SimLayout& layout, const ColliderBuffers& colliders) {
  return {Arg::of_buffer(colliders.records), Arg::of_int(layout.collider_count), Arg::of_buffer(colliders.near)};
}

std::vector<plan::KernelArg> with_colliders(std::vector<plan::KernelArg> before, const SimLayout& layout,
                                            const ColliderBuffers& colliders,
                                            const std::vector<plan::KernelArg>& after) {
  for (const Arg& a : collider_args(layout, colliders)) before.push_back(a);
  before.insert(before.end(), after.begin(), after.end());
  return before;
}

sched::TaskId add_collider_near_task(plan::SubstepPlan& plan, sched::TaskId last, const SimLayout& layout,
                                     const ColliderBuffers& colliders, plan::BufferId positions) {
  const int slots = near_slots(layout);
  if (slots == 0) return last;
  const int n = static_cast<int>(layout.x.size());
  return plan.add_task_after(
      last, plan::make_task("collision/near_lists", plan::TaskKind::collision),
      {"colliders_near",
       {0, n},
       with_colliders({Arg::of_buffer(positions)}, layout, colliders),
       {plan::WriteSpan::per_element(colliders.near, static_cast<int>(sizeof(ats_mesh_near)) * slots)}});
}

sched::TaskId add_contact_task(plan::SubstepPlan& plan, sched::TaskId last, const SimLayout& layout,
                               const ColliderBuffers& colliders, plan::BufferId positions, int iteration) {
  if (layout.colliders.empty()) return last;
  const int n = static_cast<int>(layout.x.size());
  return plan.add_task_after(
      last,
      plan::make_task(fmt::format("it{}/collision/colliders", iteration + 1), plan::TaskKind::collision, iteration, 1),
      {"particles_contact",
       {0, n},
       with_colliders({Arg::of_buffer(positions)}, layout, colliders),
       {particle_write(positions)}});
}

plan::BufferId add_friction_buffer(plan::SubstepPlan& plan, const SimLayout& layout) {
  return plan.add_buffer("material_friction", plan::BufferRole::topology, plan::bytes_of(layout.friction));
}

sched::TaskId add_friction_task(plan::SubstepPlan& plan, sched::TaskId last, const SimLayout& layout,
                                const ColliderBuffers& colliders, plan::BufferId friction, plan::BufferId positions,
                                plan::BufferId start_positions, plan::BufferId velocities, double substep_dt) {
  if (layout.colliders.empty()) return last;
  const int n = static_cast<int>(layout.x.size());
  return plan.add_task_after(
      last, plan::make_task("friction", plan::TaskKind::friction),
      {"particles_friction",
       {0, n},
       with_colliders({Arg::of_buffer(positions), Arg::of_buffer(start_positions), Arg::of_buffer(velocities)}, layout,
                      colliders, {Arg::of_float(static_cast<float>(substep_dt)), Arg::of_buffer(friction)}),
       {particle_write(positions)}});
}

}  // namespace atssim::solver
