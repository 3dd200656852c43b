#pragma once
// The data synchronisation map of asynchronous Gauss-Seidel (He et al. 2025
// §4.2.2, Fig. 5), precomputed from a schedule so that every task knows
// before the run which other-device result it merges and from which explicit
// start point. Pure: tasks, devices and predicted times only.
//
// Walking each device's slots in order, a task T on device d merges, before
// it runs, the result of one task P of every other device e when
//   - T has a predecessor on e that d has not merged yet (required: the
//     dependency is data), or
//   - with `latest`, e finished a task d has not merged yet by T's predicted
//     start (the paper's "retrieves the latest data"); the latest such task.
// Start points: the main device keeps the stream (Fig. 5). A helper's copy
// descends from the last main result it merged (its segment start); its
// first merge in a substep is a plain copy (no start point yet). A merge on
// the main device from helper task Q starts from Q's segment start; a merge
// on a helper starts from its own segment start, which then moves on.
#include <vector>

#include "sched/device_links.hpp"
#include "sched/schedule.hpp"
#include "sched/task_graph.hpp"

namespace atssim::sched {

inline constexpr TaskId kNoTask = 0xffffffffu;

struct Merge {
  TaskId consumer = 0;  // the task that runs after the merge
  DeviceId consumer_device = 0;
  TaskId producer = 0;  // whose result is merged
  DeviceId producer_device = 0;
  TaskId start = kNoTask;  // main-device task whose result is the explicit start point; kNoTask: copy
};

struct SyncMap {
  DeviceId main_device = 0;
  std::vector<Merge> merges;  // per device in slot order, devices in order
};

struct SyncMapOptions {
  bool latest = true;  // also merge the latest finished other-device result (not only data dependencies)
};

SyncMap build_sync_map(const TaskGraph& graph, const Schedule& schedule, const DeviceLinks& links, DeviceId main_device,
                       const SyncMapOptions& options = {});

}  // namespace atssim::sched
