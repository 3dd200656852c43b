#pragma once
// How a split schedule shares the work between devices (DESIGN.md "sync
// split", paper §4: balance by measured speed). Every block is cut into one
// part per device (sched::Task::part k runs on device k); these functions
// choose the fractions and carry costs from one cut to another. Pure:
// tables in, tables out.
#include <span>
#include <vector>

#include "sched/cost_table.hpp"
#include "sched/task_graph.hpp"

namespace atssim::sched {

// n equal fractions (HEFT's parts, the cut a cost file is written for).
std::vector<double> equal_fractions(std::size_t devices);

// Each device's share, inversely proportional to its time for the whole
// substep alone (the sum of its column of `costs`).
std::vector<double> speed_fractions(const CostTable& costs);

// Part k on device k; a task that is no part (Task::part -1) on device 0.
std::vector<DeviceId> part_devices(const TaskGraph& graph);

// Costs measured with every block cut into equal parts, carried to the same
// graph cut by `fractions`: a part's cost scales with its share of the
// elements (fraction · devices); a task that is no part keeps its cost.
// `graph` is the graph cut by `fractions`, with the task ids of the equal cut
// (plan::split_plan keeps every part, so both cuts number their tasks alike).
CostTable costs_for_fractions(const TaskGraph& graph, const CostTable& equal_costs, std::span<const double> fractions);

// After a re-cut moved each task's share of its whole task from `before` to
// `after`: the factor its costs scale by (1 where it had no share before).
std::vector<double> share_factors(std::span<const double> before, std::span<const double> after);

}  // namespace atssim::sched
