#pragma once
// Lower bounds on any schedule's makespan, to judge a scheduler's result.
#include "sched/cost_table.hpp"
#include "sched/task_graph.hpp"

namespace atssim::sched {

// Longest path where every task costs its minimum over devices and no edge
// costs anything (both ends could share a device): no schedule is shorter.
double critical_path_bound(const TaskGraph& graph, const CostTable& costs);

// Every task needs at least its minimum cost on some device and the devices
// share the work: sum of minimum costs / device count.
double work_bound(const CostTable& costs);

// The larger of the two.
double makespan_lower_bound(const TaskGraph& graph, const CostTable& costs);

}  // namespace atssim::sched
