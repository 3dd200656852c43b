#include "sched/task_merging.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

#include <fmt/format.h>

#include "util/error.hpp"

namespace atssim::sched {

namespace {

constexpr TaskId kUngrouped = std::numeric_limits<TaskId>::max();

// group_of[t]: index of the group holding original task t, or kUngrouped.
std::vector<TaskId> group_index(const TaskGraph& graph, std::span<const std::vector<TaskId>> groups) {
  std::vector<TaskId> group_of(graph.size(), kUngrouped);
  for (TaskId g = 0; g < groups.size(); ++g) {
    if (groups[g].empty()) throw internal_error(fmt::format("task merging: group {} is empty", g));
    for (TaskId t : groups[g]) {
      if (t >= graph.size()) {
        throw internal_error(
            fmt::format("task merging: group {} names task {}, the graph has {} tasks", g, t, graph.size()));
      }
      if (group_of[t] != kUngrouped) {
        throw internal_error(fmt::format("task merging: task '{}' is in more than one group", graph.task(t).name));
      }
      group_of[t] = g;
    }
  }
  return group_of;
}

Task merged_task(const TaskGraph& graph, std::span<const TaskId> members) {
  const Task& first = graph.task(members.front());
  Task merged = first;
  merged.name.clear();
  for (TaskId t : members) {
    const Task& m = graph.task(t);
    merged.name += (merged.name.empty() ? "" : "+") + m.name;
    if (m.kind != first.kind) merged.kind = kMixedKind;
    if (m.part != first.part) merged.part = -1;
    if (m.iteration != first.iteration) merged.iteration = -1;
    if (m.block != first.block) merged.block = -1;
  }
  return merged;
}

}  // namespace

MergedGraph merge_tasks(const TaskGraph& graph, const CostTable& costs, std::span<const std::vector<TaskId>> groups) {
  if (costs.tasks != graph.size()) {
    throw internal_error(
        fmt::format("task merging: the cost table has {} tasks, the graph {}", costs.tasks, graph.size()));
  }
  const auto group_of = group_index(graph, groups);
  const auto topo = graph.topological_order();
  std::vector<std::uint32_t> position(graph.size());
  for (std::uint32_t i = 0; i < topo.size(); ++i) position[topo[i]] = i;

  MergedGraph out;
  out.merged_id.assign(graph.size(), 0);
  std::vector<TaskId> group_task(groups.size(), kUngrouped);
  // New tasks in original id order; a group appears where its first member is.
  for (TaskId t = 0; t < graph.size(); ++t) {
    const TaskId g = group_of[t];
    if (g == kUngrouped) {
      out.merged_id[t] = out.graph.add_task(graph.task(t));
      out.members.push_back({t});
      continue;
    }
    if (group_task[g] == kUngrouped) {
      std::vector<TaskId> members = groups[g];
      std::sort(members.begin(), members.end(), [&](TaskId a, TaskId b) { return position[a] < position[b]; });
      group_task[g] = out.graph.add_task(merged_task(graph, members));
      out.members.push_back(std::move(members));
    }
    out.merged_id[t] = group_task[g];
  }

  out.costs = CostTable(out.graph.size(), costs.devices, 0.0);
  for (TaskId m = 0; m < out.graph.size(); ++m) {
    for (TaskId t : out.members[m]) {
      for (DeviceId d = 0; d < costs.devices; ++d) out.costs.at(m, d) += costs.at(t, d);
    }
  }
  for (TaskId t = 0; t < graph.size(); ++t) {
    for (const Edge& e : graph.successors(t)) {
      const TaskId from = out.merged_id[e.from];
      const TaskId to = out.merged_id[e.to];
      if (from != to) out.graph.add_edge(from, to, e.comm);
    }
  }
  try {
    out.graph.topological_order();
  } catch (const Error& e) {
    throw Error(std::string("task merging: the groups create a cycle (a group's members are linked through an "
                            "outside task): ") +
                    e.what(),
                e.kind());
  }
  return out;
}

std::vector<std::vector<TaskId>> consecutive_groups(std::span<const TaskId> sequence, std::size_t group_size) {
  if (group_size == 0) throw internal_error("task merging: group size must be at least 1");
  std::vector<std::vector<TaskId>> groups;
  for (std::size_t i = 0; i < sequence.size(); i += group_size) {
    const std::size_t end = std::min(sequence.size(), i + group_size);
    groups.emplace_back(sequence.begin() + i, sequence.begin() + end);
  }
  return groups;
}

std::size_t profitable_merge_size(double fast_ms, double slow_ms, double switch_ms) {
  if (!(slow_ms > fast_ms)) return 0;
  // k·(slow − fast) > switch  ⇔  k > switch / (slow − fast)
  const double k = std::floor(switch_ms / (slow_ms - fast_ms)) + 1.0;
  return static_cast<std::size_t>(std::max(1.0, k));
}

Schedule expand_merged_schedule(const Schedule& merged, const MergedGraph& merge, const CostTable& original_costs) {
  std::vector<std::vector<Slot>> devices(merged.devices.size());
  for (DeviceId d = 0; d < merged.devices.size(); ++d) {
    for (const Slot& slot : merged.devices[d]) {
      double t = slot.start_ms;
      for (TaskId member : merge.members.at(slot.task)) {
        const double finish = t + original_costs.at(member, d);
        devices[d].push_back({member, t, finish});
        t = finish;
      }
    }
  }
  return assemble_schedule(original_costs.tasks, std::move(devices), merged.device_ready_ms);
}

}  // namespace atssim::sched
