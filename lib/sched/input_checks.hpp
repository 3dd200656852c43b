#pragma once
// One place that checks the scheduler's inputs describe one problem, so every
// algorithm fails the same way with a message a user can act on.
#include <span>

#include "sched/cost_table.hpp"
#include "sched/device_links.hpp"
#include "sched/task_graph.hpp"

namespace atssim::sched {

// Throws atssim::Error when: the cost table and graph disagree on the number
// of tasks, the cost table and links disagree on the number of devices, a
// cost is negative or NaN, a task can run on no device, a link or edge weight
// is negative or not finite, or device_ready_ms is neither empty nor one
// finite value per device.
void check_scheduling_inputs(const TaskGraph& graph, const CostTable& costs, const DeviceLinks& links,
                             std::span<const double> device_ready_ms = {});

}  // namespace atssim::sched
