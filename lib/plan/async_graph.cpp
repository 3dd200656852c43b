#include "plan/async_graph.hpp"

#include <map>

#include <fmt/format.h>

#include "util/error.hpp"

namespace atssim::plan {

SubstepPlan async_graph(const SubstepPlan& serial, int depth) {
  // The scene reader keeps solver.async_depth in 1..64.
  if (depth < 1) throw internal_error(fmt::format("async depth {} must be at least 1", depth));
  if (depth == 1) return serial;
  SubstepPlan out = serial;
  out.graph = sched::TaskGraph();
  for (const sched::Task& t : serial.graph.tasks()) out.graph.add_task(t);

  const auto order = serial.graph.topological_order();
  std::vector<sched::TaskId> before, after;             // tasks outside the iterations
  std::map<int, std::map<int, sched::TaskId>> last_of;  // iteration -> kind -> last task
  std::map<int, sched::TaskId> previous_of_kind;
  bool seen_iteration = false;
  for (sched::TaskId t : order) {
    const sched::Task& task = serial.graph.task(t);
    if (task.iteration < 0) {
      (seen_iteration ? after : before).push_back(t);
      continue;
    }
    seen_iteration = true;
    if (traits(kind_of(task)).serial) {
      // Ends its iteration: after every kind's last task of it; every kind's
      // next task waits for it (through previous_of_kind below).
      for (const auto& [kind, last] : last_of[task.iteration]) out.graph.add_edge(last, t);
      for (auto& [kind, previous] : previous_of_kind) previous = t;
      last_of[task.iteration][task.kind] = t;
      continue;
    }
    if (auto it = previous_of_kind.find(task.kind); it != previous_of_kind.end()) out.graph.add_edge(it->second, t);
    previous_of_kind[task.kind] = t;
    last_of[task.iteration][task.kind] = t;
    if (auto window = last_of.find(task.iteration - depth); window != last_of.end()) {
      for (const auto& [kind, last] : window->second) out.graph.add_edge(last, t);
    }
  }
  // Before/after tasks chain as in the serial order, around all iteration tasks.
  for (std::size_t i = 1; i < before.size(); ++i) out.graph.add_edge(before[i - 1], before[i]);
  for (std::size_t i = 1; i < after.size(); ++i) out.graph.add_edge(after[i - 1], after[i]);
  for (sched::TaskId t : order) {
    const sched::Task& task = serial.graph.task(t);
    if (task.iteration < 0) continue;
    if (!before.empty() && out.graph.predecessors(t).empty()) out.graph.add_edge(before.back(), t);
  }
  if (!after.empty()) {
    for (const auto& [iteration, kinds] : last_of) {
      for (const auto& [kind, last] : kinds) {
        if (out.graph.successors(last).empty()) out.graph.add_edge(last, after.front());
      }
    }
  }
  return out;
}

}  // namespace atssim::plan
