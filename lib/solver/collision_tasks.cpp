#include "solver/collision_tasks.hpp"

#include <fmt/format.h>

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

plan::BufferId add_collider_buffer(plan::SubstepPlan& plan, const SimLayout& layout) {
  return plan.add_buffer("colliders", plan::BufferRole::colliders, plan::bytes_of(layout.colliders));
}

sched::TaskId add_contact_task(plan::SubstepPlan& plan, sched::TaskId last, const SimLayout& layout,
                               plan::BufferId colliders, plan::BufferId positions, int iteration) {
  if (layout.colliders.empty()) return last;
  const int n = static_cast<int>(layout.x.size());
  return plan.add_task_after(
      last,
      plan::make_task(fmt::format("it{}/collision/colliders", iteration + 1), plan::TaskKind::collision, iteration, 1),
      {"particles_contact",
       {0, n},
       {Arg::of_buffer(positions), Arg::of_buffer(colliders), Arg::of_int(layout.collider_count)},
       {particle_write(positions)}});
}

plan::BufferId add_friction_buffer(plan::SubstepPlan& plan, const SimLayout& layout) {
  return plan.add_buffer("material_friction", plan::BufferRole::topology, plan::bytes_of(layout.friction));
}

sched::TaskId add_friction_task(plan::SubstepPlan& plan, sched::TaskId last, const SimLayout& layout,
                                plan::BufferId colliders, plan::BufferId friction, plan::BufferId positions,
                                plan::BufferId start_positions, plan::BufferId velocities, double substep_dt) {
  if (layout.colliders.empty()) return last;
  const int n = static_cast<int>(layout.x.size());
  return plan.add_task_after(last, plan::make_task("friction", plan::TaskKind::friction),
                             {"particles_friction",
                              {0, n},
                              {Arg::of_buffer(positions), Arg::of_buffer(start_positions), Arg::of_buffer(velocities),
                               Arg::of_buffer(colliders), Arg::of_int(layout.collider_count),
                               Arg::of_float(static_cast<float>(substep_dt)), Arg::of_buffer(friction)},
                              {particle_write(positions)}});
}

}  // namespace atssim::solver
