#include "sched/cpop.hpp"

#include <algorithm>
#include <cmath>

#include "sched/input_checks.hpp"
#include "sched/rank.hpp"

namespace atssim::sched {

namespace {

std::vector<double> cpop_priority(const CompactGraph& graph, const CostTable& costs, const DeviceLinks& links) {
  auto priority = upward_rank(graph, costs, links);
  const auto down = downward_rank(graph, costs, links);
  for (std::size_t i = 0; i < priority.size(); ++i) priority[i] += down[i];
  return priority;
}

std::vector<TaskId> critical_path(const CompactGraph& graph, std::span<const double> priority) {
  if (graph.size() == 0) return {};
  TaskId current = graph.topological_order().front();  // a source
  for (TaskId t = 0; t < graph.size(); ++t) {
    if (graph.predecessors(t).empty() && priority[t] > priority[current]) current = t;
  }
  const double length = priority[current];
  const double tol = 1e-9 * std::max(1.0, std::abs(length));
  std::vector<TaskId> path{current};
  for (;;) {
    const auto succ = graph.successors(current);
    auto next = std::find_if(succ.begin(), succ.end(),
                             [&](const CompactEdge& e) { return std::abs(priority[e.task] - length) <= tol; });
    if (next == succ.end()) break;
    current = next->task;
    path.push_back(current);
  }
  return path;
}

// The device that runs every critical-path task in the least total time.
DeviceId critical_path_device(const CostTable& costs, std::span<const TaskId> path) {
  DeviceId best = kNoDevice;
  double best_sum = kCannotRun;
  for (DeviceId d = 0; d < costs.devices; ++d) {
    double sum = 0.0;
    for (TaskId t : path) sum += costs.at(t, d);
    if (sum < best_sum) {
      best_sum = sum;
      best = d;
    }
  }
  return best;
}

}  // namespace

std::vector<TaskId> cpop_critical_path(const TaskGraph& graph, const CostTable& costs, const DeviceLinks& links) {
  check_scheduling_inputs(graph, costs, links);
  const CompactGraph compact(graph);
  return critical_path(compact, cpop_priority(compact, costs, links));
}

Schedule schedule_cpop(const TaskGraph& graph, const CostTable& costs, const DeviceLinks& links,
                       const ListOptions& options) {
  check_scheduling_inputs(graph, costs, links, options.device_ready_ms);
  const CompactGraph compact(graph);
  const auto priority = cpop_priority(compact, costs, links);
  const auto path = critical_path(compact, priority);
  const DeviceId cp_device = critical_path_device(costs, path);
  std::vector<bool> on_path(graph.size(), false);
  for (TaskId t : path) on_path[t] = true;

  ScheduleBuilder builder(graph, compact, costs, links, options);
  ReadyList ready(compact, priority);
  std::vector<SlotChoice> choices;
  while (!ready.empty()) {
    const TaskId task = ready.pop();
    if (on_path[task] && cp_device != kNoDevice) {
      builder.place(task, builder.earliest_finish(task, cp_device));
      continue;
    }
    builder.earliest_finish_all(task, choices);
    SlotChoice best = choices.front();
    for (const SlotChoice& c : choices) {
      if (c.finish_ms < best.finish_ms) best = c;
    }
    builder.place(task, best);
  }
  return std::move(builder).finish();
}

}  // namespace atssim::sched
