#include "plan/substep_plan.hpp"

#include <fmt/format.h>

#include "util/error.hpp"

namespace atssim::plan {

BufferId SubstepPlan::add_buffer(std::string name, BufferRole role, std::vector<std::byte> initial) {
  buffers.push_back({std::move(name), role, std::move(initial)});
  return static_cast<BufferId>(buffers.size() - 1);
}

sched::TaskId SubstepPlan::add_task(sched::Task task, std::vector<KernelLaunch> task_launches) {
  const sched::TaskId id = graph.add_task(std::move(task));
  launches.push_back(std::move(task_launches));
  return id;
}

sched::TaskId SubstepPlan::add_task_after(sched::TaskId after, sched::Task task, KernelLaunch launch) {
  std::vector<KernelLaunch> one;
  one.push_back(std::move(launch));
  const sched::TaskId id = add_task(std::move(task), std::move(one));
  graph.add_edge(after, id);
  return id;
}

BufferId SubstepPlan::find_buffer(BufferRole role) const {
  BufferId found = -1;
  for (BufferId b = 0; b < static_cast<BufferId>(buffers.size()); ++b) {
    if (buffers[b].role != role) continue;
    if (found >= 0) {
      throw internal_error(fmt::format("plan '{}': buffers '{}' and '{}' both have the role {}", program,
                                       buffers[found].name, buffers[b].name, to_string(role)));
    }
    found = b;
  }
  return found;
}

BufferId SubstepPlan::buffer(BufferRole role) const {
  const BufferId b = find_buffer(role);
  if (b < 0) throw internal_error(fmt::format("plan '{}' has no buffer of role {}", program, to_string(role)));
  return b;
}

std::string_view to_string(BufferRole role) {
  switch (role) {
    case BufferRole::positions:
      return "positions";
    case BufferRole::velocities:
      return "velocities";
    case BufferRole::start_positions:
      return "start_positions";
    case BufferRole::inertia_target:
      return "inertia_target";
    case BufferRole::elements:
      return "elements";
    case BufferRole::topology:
      return "topology";
    case BufferRole::multipliers:
      return "multipliers";
    case BufferRole::scratch:
      return "scratch";
    case BufferRole::replica:
      return "replica";
    case BufferRole::snapshot:
      return "snapshot";
    case BufferRole::results:
      return "results";
    case BufferRole::colliders:
      return "colliders";
    case BufferRole::cache:
      return "cache";
    case BufferRole::cache_state:
      return "cache_state";
    case BufferRole::carried:
      return "carried";
  }
  return "?";
}

}  // namespace atssim::plan
