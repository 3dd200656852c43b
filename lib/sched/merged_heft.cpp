#include "sched/merged_heft.hpp"

#include <algorithm>
#include <map>
#include <tuple>

#include "sched/heft.hpp"
#include "sched/task_merging.hpp"
#include "util/error.hpp"

namespace atssim::sched {

std::vector<std::vector<TaskId>> block_groups(const TaskGraph& graph, std::size_t blocks_per_group) {
  if (blocks_per_group == 0) throw internal_error("task merging: blocks_per_group must be at least 1");
  // (kind, iteration) -> block -> its tasks (parts), in id order.
  std::map<std::pair<int, int>, std::map<int, std::vector<TaskId>>> blocks;
  for (TaskId t = 0; t < graph.size(); ++t) {
    const Task& task = graph.task(t);
    if (task.block >= 0) blocks[{task.kind, task.iteration}][task.block].push_back(t);
  }
  std::vector<std::vector<TaskId>> groups;
  for (const auto& [key, by_block] : blocks) {
    std::vector<TaskId> group;
    std::size_t in_group = 0;
    for (const auto& [block, tasks] : by_block) {
      group.insert(group.end(), tasks.begin(), tasks.end());
      if (++in_group == blocks_per_group) {
        if (group.size() >= 2) groups.push_back(group);
        group.clear();
        in_group = 0;
      }
    }
    if (group.size() >= 2) groups.push_back(group);
  }
  return groups;
}

MergedHeft schedule_heft_merging(const TaskGraph& graph, const CostTable& costs, const DeviceLinks& links,
                                 std::span<const std::size_t> blocks_per_group, double min_gain) {
  MergedHeft best;
  best.schedule = schedule_heft_or_one_device(graph, costs, links);
  best.unmerged_makespan_ms = best.schedule.makespan_ms;
  best.group.assign(graph.size(), -1);
  std::vector<std::size_t> sizes(blocks_per_group.begin(), blocks_per_group.end());
  std::sort(sizes.begin(), sizes.end());
  for (std::size_t k : sizes) {
    const std::vector<std::vector<TaskId>> groups = block_groups(graph, k);
    if (groups.empty()) continue;
    MergedGraph merged;
    try {
      merged = merge_tasks(graph, costs, groups);
    } catch (const Error&) {
      continue;  // members linked through an outside task: not a chain of blocks
    }
    const Schedule s = schedule_heft_or_one_device(merged.graph, merged.costs, links);
    if (!(s.makespan_ms < best.schedule.makespan_ms * (1.0 - min_gain))) continue;
    best.schedule = expand_merged_schedule(s, merged, costs);
    best.blocks_per_group = k;
    best.groups = groups.size();
    best.group.assign(graph.size(), -1);
    for (std::size_t g = 0; g < groups.size(); ++g) {
      for (TaskId t : groups[g]) best.group[t] = static_cast<int>(g);
    }
  }
  return best;
}

}  // namespace atssim::sched
