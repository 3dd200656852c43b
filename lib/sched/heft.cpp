#include "sched/heft.hpp"

#include <cmath>

#include <fmt/format.h>

#include "sched/fixed_assignment.hpp"
#include "sched/input_checks.hpp"
#include "sched/rank.hpp"
#include "util/error.hpp"

namespace atssim::sched {

Schedule schedule_heft(const TaskGraph& graph, const CostTable& costs, const DeviceLinks& links,
                       const HeftOptions& options) {
  check_scheduling_inputs(graph, costs, links, options.device_ready_ms);
  const CompactGraph compact(graph);
  std::vector<double> rank;
  if (options.priority.empty()) {
    rank = upward_rank(compact, costs, links);
  } else if (options.priority.size() != graph.size()) {
    throw internal_error(fmt::format("HEFT: {} priorities given for {} tasks", options.priority.size(), graph.size()));
  } else {
    for (TaskId t = 0; t < graph.size(); ++t) {
      if (!std::isfinite(options.priority[t])) {
        throw internal_error(fmt::format("HEFT: task '{}' has priority {}; priorities must be finite",
                                         graph.task(t).name, options.priority[t]));
      }
    }
  }
  const std::span<const double> priority = options.priority.empty() ? std::span<const double>(rank) : options.priority;

  ScheduleBuilder builder(graph, compact, costs, links, options);
  ReadyList ready(compact, priority);
  std::vector<SlotChoice> choices;
  while (!ready.empty()) {
    const TaskId task = ready.pop();
    builder.earliest_finish_all(task, choices);
    SlotChoice best = choices.front();
    for (const SlotChoice& c : choices) {
      if (c.finish_ms < best.finish_ms) best = c;  // strict: ties keep the lower device id
    }
    builder.place(task, best);
  }
  return std::move(builder).finish();
}

Schedule schedule_heft_or_one_device(const TaskGraph& graph, const CostTable& costs, const DeviceLinks& links,
                                     const HeftOptions& options) {
  Schedule best = schedule_heft(graph, costs, links, options);
  for (std::size_t d = 0; d < costs.devices; ++d) {
    bool runs_all = true;
    for (TaskId t = 0; t < graph.size() && runs_all; ++t) runs_all = std::isfinite(costs.at(t, d));
    if (!runs_all) continue;
    const std::vector<DeviceId> one(graph.size(), static_cast<DeviceId>(d));
    Schedule alone = schedule_fixed(graph, costs, links, one, options.device_ready_ms);
    if (alone.makespan_ms < best.makespan_ms) best = std::move(alone);
  }
  return best;
}

}  // namespace atssim::sched
