#pragma once
// Reference optimum for tiny DAGs (≤ 8 tasks), independent of the list
// schedulers: branch and bound over every semi-active schedule.
//
// Any schedule can be left-shifted, task by task in start order, without
// growing its makespan; then each task starts at max(its device's previous
// finish, its inputs' arrival). So it suffices to enumerate the order in
// which tasks are appended to devices, and only orders with non-decreasing
// start times (positive costs make that order unique up to ties).
#include <span>

#include "sched/cost_table.hpp"
#include "sched/device_links.hpp"
#include "sched/task_graph.hpp"

namespace atssim::sched::test {

// Minimum makespan over all schedules. The search starts unbounded: its
// first bound is the first complete schedule it builds, so nothing a
// scheduler under test computed can leak into the reference.
double optimal_makespan(const TaskGraph& graph, const CostTable& costs, const DeviceLinks& links,
                        std::span<const double> device_ready_ms = {});

}  // namespace atssim::sched::test
