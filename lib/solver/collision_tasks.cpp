#include "solver/collision_tasks.hpp"

#include <fmt/format.h>

namespace atssim::solver {

sched::TaskId add_ground_task(SubstepPlan& plan, sched::TaskId last, const SimLayout& layout,
                              BufferId positions, int iteration) {
  if (!layout.has_ground) return last;
  const int n = static_cast<int>(layout.x.size());
  const sched::TaskId t = plan.add_task(
      {fmt::format("it{}/collision/ground", iteration + 1), "collision", iteration, 0},
      {{"particles_ground", static_cast<std::size_t>(n),
        {KernelArg::of_buffer(positions), KernelArg::of_float(layout.ground_y), KernelArg::of_int(0),
         KernelArg::of_int(n)},
        2}});
  plan.graph.add_edge(last, t);
  return t;
}

}  // namespace atssim::solver
