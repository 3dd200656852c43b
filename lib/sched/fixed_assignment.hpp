#pragma once
// Predicted times for a schedule whose device assignment is already chosen
// (e.g. the proportional `split` of a color block, or everything on one
// device): tasks in topological order, each appended to its device's
// in-order queue at the earliest time its inputs are there.
#include <vector>

#include "sched/schedule.hpp"

namespace atssim::sched {

// `device[t]` is the device of task t. Throws atssim::Error when a task is
// assigned to a device that cannot run it.
Schedule schedule_fixed(const TaskGraph& graph, const CostTable& costs, const DeviceLinks& links,
                        const std::vector<DeviceId>& device, const std::vector<double>& device_ready_ms = {});

}  // namespace atssim::sched
