#pragma once
// Task merging chosen at run time (paper §4.1.1): HEFT on the graph as it
// is, and on the graph with its colour blocks merged in groups, and the
// schedule predicted to end first.
//
// Why at run time: whether a merge pays depends on the measured costs (the
// blocks' times on each device and the switch cost between them), which are
// known only after profiling, and change when the costs are refitted. HEFT
// places one task at a time by its own finish; a chain of small blocks whose
// first lands on the slower device stays there when a move costs more than
// one block saves (task_merging.hpp, Fig. 3), and a block cut into parts
// pays a hop per part. Merging gives HEFT tasks big enough to move.
//
// Candidates, each a partition of the colour-block tasks (Task::block >= 0)
// of one kind and iteration, in block order (tasks without a block stay
// alone):
//   blocks_per_group 1: the parts of each block (a block cut between the
//     devices, Task::part) as one task, so it runs whole on one device;
//   k >= 2: every k consecutive blocks, all their parts, as one task.
// A candidate whose groups would make a cycle (members linked through an
// outside task) is skipped. The merged schedule is expanded back to the
// original tasks (expand_merged_schedule), so the executor runs the same
// tasks; only their devices and order change, never a result.
#include <cstddef>
#include <span>
#include <vector>

#include "sched/cost_table.hpp"
#include "sched/device_links.hpp"
#include "sched/schedule.hpp"
#include "sched/task_graph.hpp"

namespace atssim::sched {

struct MergedHeft {
  Schedule schedule;                  // of the original tasks
  std::size_t blocks_per_group = 0;   // the merge chosen; 0: none
  std::vector<int> group;             // per original task: its merged task, -1 when it ran alone
  std::size_t groups = 0;             // merged tasks (of two or more original ones)
  double unmerged_makespan_ms = 0.0;  // HEFT's predicted makespan without merging
};

// The groups of candidate `blocks_per_group` (see above); only groups of two
// tasks or more.
std::vector<std::vector<TaskId>> block_groups(const TaskGraph& graph, std::size_t blocks_per_group);

// schedule_heft_or_one_device on the graph and on each candidate of
// `blocks_per_group` (e.g. {1, 2, 4, 8}); a merge is kept only when its
// makespan is shorter by more than `min_gain` (relative) than every
// schedule with fewer merged blocks. The default, 10 %, is the scheduler's
// prediction error measured on two sub-devices (docs/benchmarks.md): with
// 1 %, runs on them chose merges predicted 1-3 % shorter, and ran
// 1.18-1.31x slower than without (docs/benchmarks.md, "Task merging at run
// time").
MergedHeft schedule_heft_merging(const TaskGraph& graph, const CostTable& costs, const DeviceLinks& links,
                                 std::span<const std::size_t> blocks_per_group, double min_gain = 0.10);

}  // namespace atssim::sched
