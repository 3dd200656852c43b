#include "solver/collision_tasks.hpp"

#include <fmt/format.h>

#include "solver/layout/particle_tables.hpp"

namespace atssim::solver {

sched::TaskId add_ground_task(plan::SubstepPlan& plan, sched::TaskId last, const SimLayout& layout,
                              plan::BufferId positions, int iteration) {
  if (!layout.has_ground) return last;
  const int n = static_cast<int>(layout.x.size());
  return plan.add_task_after(
      last,
      plan::make_task(fmt::format("it{}/collision/ground", iteration + 1), plan::TaskKind::collision, iteration, 0),
      {"particles_ground",
       {0, n},
       {plan::KernelArg::of_buffer(positions), plan::KernelArg::of_float(layout.ground_y)},
       {particle_write(positions)}});
}

}  // namespace atssim::solver
