#pragma once
// Task merging (paper §4.1.1, Fig. 3) as a graph transformation.
//
// Why: with device times t1 < t2 and switch cost tc, a chain of small blocks
// whose first block lands on the slow device stays there whenever
// t2 < tc + t1, leaving the fast device idle (8·t2 in Fig. 3a). Merging k
// consecutive blocks into one task moves it once k·t2 > tc + k·t1
// (tc + 8·t1 in Fig. 3b).
//
// Rule: each group of tasks becomes one task that runs its members back to
// back on one device, in topological order. Its cost on a device is the sum
// of the members' costs (inf if any member cannot run there). Edges between
// members disappear (same device, no transfer); an edge between a member and
// an outside task becomes an edge of the merged task with the same weight
// (two such edges to one outside task keep the larger weight). The merged
// task is named "first+…+last", keeps kind/iteration/block when all members
// share them (else kMixedKind / -1). Tasks outside every group are unchanged.
// A group whose members are linked through an outside task would make a
// cycle: that is an error naming it.
#include <cstddef>
#include <span>
#include <vector>

#include "sched/cost_table.hpp"
#include "sched/schedule.hpp"
#include "sched/task_graph.hpp"

namespace atssim::sched {

struct MergedGraph {
  TaskGraph graph;
  CostTable costs;
  std::vector<TaskId> merged_id;             // original task → its task in `graph`
  std::vector<std::vector<TaskId>> members;  // task in `graph` → original tasks, in run order
};

MergedGraph merge_tasks(const TaskGraph& graph, const CostTable& costs, std::span<const std::vector<TaskId>> groups);

// Splits `sequence` into consecutive groups of `group_size` (the last may be
// shorter): the paper's "merge every four bending blocks".
std::vector<std::vector<TaskId>> consecutive_groups(std::span<const TaskId> sequence, std::size_t group_size);

// Smallest k with k·slow > switch + k·fast (a merged block of k tasks then
// prefers the fast device); 0 when no k does (slow <= fast).
std::size_t profitable_merge_size(double fast_ms, double slow_ms, double switch_ms);

// A schedule of the merged graph as a schedule of the original tasks: each
// merged slot is split into its members' slots, back to back, in run order.
Schedule expand_merged_schedule(const Schedule& merged, const MergedGraph& merge, const CostTable& original_costs);

}  // namespace atssim::sched
