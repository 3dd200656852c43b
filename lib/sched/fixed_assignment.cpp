#include "sched/fixed_assignment.hpp"

#include <algorithm>

#include <fmt/format.h>

#include "util/error.hpp"

namespace atssim::sched {

Schedule schedule_fixed(const TaskGraph& graph, const CostTable& costs, const DeviceLinks& links,
                        const std::vector<DeviceId>& device, const std::vector<double>& device_ready_ms) {
  if (device.size() != graph.size() || costs.tasks != graph.size()) {
    throw internal_error(fmt::format("schedule_fixed: {} assignments and {} cost rows for {} tasks", device.size(),
                                     costs.tasks, graph.size()));
  }
  std::vector<double> ready = device_ready_ms;
  ready.resize(costs.devices, 0.0);
  std::vector<double> finish(graph.size(), 0.0);
  std::vector<std::vector<Slot>> slots(costs.devices);
  for (TaskId t : graph.topological_order()) {
    const DeviceId d = device[t];
    if (d >= costs.devices || !costs.can_run(t, d)) {
      throw internal_error(fmt::format("schedule_fixed: task '{}' is assigned to device {}, which cannot run it",
                                       graph.task(t).name, d));
    }
    double start = ready[d];
    for (const Edge& e : graph.predecessors(t)) {
      start = std::max(start, finish[e.from] + links.comm_ms(e.comm, device[e.from], d));
    }
    finish[t] = start + costs.at(t, d);
    ready[d] = finish[t];
    slots[d].push_back({t, start, finish[t]});
  }
  return assemble_schedule(graph.size(), std::move(slots), device_ready_ms);
}

}  // namespace atssim::sched
