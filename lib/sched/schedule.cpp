#include "sched/schedule.hpp"

#include <algorithm>
#include <numeric>

#include <fmt/format.h>

#include "util/error.hpp"

namespace atssim::sched {

const Slot& Schedule::slot(TaskId task) const {
  const Placement& p = placement.at(task);
  if (p.device == kNoDevice) {
    throw internal_error(fmt::format("schedule: task {} is not scheduled", task));
  }
  return devices.at(p.device).at(p.index);
}

Schedule assemble_schedule(std::size_t task_count, std::vector<std::vector<Slot>> devices,
                           std::vector<double> device_ready_ms) {
  Schedule s;
  s.devices = std::move(devices);
  s.placement.assign(task_count, Placement{});
  s.device_ready_ms = std::move(device_ready_ms);
  if (s.device_ready_ms.empty()) s.device_ready_ms.assign(s.devices.size(), 0.0);
  for (DeviceId d = 0; d < s.devices.size(); ++d) {
    auto& slots = s.devices[d];
    std::stable_sort(slots.begin(), slots.end(), [](const Slot& a, const Slot& b) {
      return a.start_ms < b.start_ms || (a.start_ms == b.start_ms && a.finish_ms < b.finish_ms);
    });
    for (std::uint32_t i = 0; i < slots.size(); ++i) {
      if (slots[i].task < task_count) s.placement[slots[i].task] = {d, i};
      s.makespan_ms = std::max(s.makespan_ms, slots[i].finish_ms);
    }
  }
  return s;
}

Schedule replay_on_device0(const Schedule& schedule, const CostTable& costs, std::size_t devices) {
  std::vector<TaskId> order(schedule.task_count());
  std::iota(order.begin(), order.end(), 0);
  std::stable_sort(order.begin(), order.end(),
                   [&](TaskId a, TaskId b) { return schedule.slot(a).start_ms < schedule.slot(b).start_ms; });
  std::vector<std::vector<Slot>> lanes(std::max<std::size_t>(devices, 1));
  double clock = 0.0;
  for (TaskId t : order) {
    lanes[0].push_back({t, clock, clock + costs.at(t, 0)});
    clock += costs.at(t, 0);
  }
  return assemble_schedule(order.size(), std::move(lanes));
}

}  // namespace atssim::sched
