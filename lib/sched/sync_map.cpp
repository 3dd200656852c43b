#include "sched/sync_map.hpp"

#include <algorithm>

namespace atssim::sched {

SyncMap build_sync_map(const TaskGraph& graph, const Schedule& schedule, const DeviceLinks& links, DeviceId main_device,
                       const SyncMapOptions& options) {
  const std::size_t devices = schedule.devices.size();
  SyncMap map;
  map.main_device = main_device;

  // Helper segment starts, per helper task: the main task whose result the
  // helper's copy descends from when the task runs (kNoTask before any).
  std::vector<TaskId> segment_start_at(graph.size(), kNoTask);

  // Main device last, so helper segment starts are known when it merges.
  std::vector<DeviceId> order;
  for (DeviceId d = 0; d < devices; ++d) {
    if (d != main_device) order.push_back(d);
  }
  order.push_back(main_device);

  std::vector<std::vector<Merge>> per_device(devices);
  for (DeviceId d : order) {
    std::vector<int> have(devices, -1);  // per other device: index of the last slot merged
    TaskId segment_start = kNoTask;
    for (const Slot& slot : schedule.devices[d]) {
      const TaskId t = slot.task;
      std::vector<int> want(devices, -1);
      for (const Edge& e : graph.predecessors(t)) {
        const DeviceId p = schedule.device_of(e.from);
        if (p != d) want[p] = std::max(want[p], static_cast<int>(schedule.placement[e.from].index));
      }
      if (options.latest) {
        for (DeviceId e = 0; e < devices; ++e) {
          if (e == d) continue;
          const auto& slots = schedule.devices[e];
          // The last slot of e that is done (plus the hop) by T's start.
          int latest = -1;
          for (int i = static_cast<int>(slots.size()) - 1; i >= 0; --i) {
            if (slots[i].finish_ms + links.comm_ms(0.0, e, d) <= slot.start_ms) {
              latest = i;
              break;
            }
          }
          want[e] = std::max(want[e], latest);
        }
      }
      for (DeviceId e = 0; e < devices; ++e) {
        if (e == d || want[e] <= have[e]) continue;
        have[e] = want[e];
        const TaskId producer = schedule.devices[e][want[e]].task;
        Merge m{t, d, producer, e, kNoTask};
        if (d == main_device) {
          m.start = segment_start_at[producer];
        } else {
          m.start = segment_start;  // kNoTask on the first merge: a copy
          if (e == main_device) segment_start = producer;
        }
        per_device[d].push_back(m);
      }
      if (d != main_device) segment_start_at[t] = segment_start;
    }
  }
  for (DeviceId d = 0; d < devices; ++d) {
    map.merges.insert(map.merges.end(), per_device[d].begin(), per_device[d].end());
  }
  return map;
}

}  // namespace atssim::sched
