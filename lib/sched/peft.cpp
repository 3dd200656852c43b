#include "sched/peft.hpp"

#include <algorithm>

#include "sched/input_checks.hpp"

namespace atssim::sched {

namespace {

CostTable build_oct(const CompactGraph& graph, const CostTable& costs, const DeviceLinks& links) {
  const std::size_t nd = costs.devices;
  CostTable oct(graph.size(), nd, 0.0);
  const auto topo = graph.topological_order();
  for (auto it = topo.rbegin(); it != topo.rend(); ++it) {
    const TaskId i = *it;
    for (DeviceId p = 0; p < nd; ++p) {
      double worst = 0.0;
      for (const CompactEdge& e : graph.successors(i)) {
        double best = kCannotRun;
        for (DeviceId w = 0; w < nd; ++w) {
          const double c = costs.at(e.task, w);
          if (!(c < kCannotRun)) continue;
          best = std::min(best, oct.at(e.task, w) + c + links.comm_ms(e.comm, p, w));
        }
        worst = std::max(worst, best);
      }
      oct.at(i, p) = worst;
    }
  }
  return oct;
}

std::vector<double> oct_rank(const CostTable& oct, const CostTable& costs) {
  std::vector<double> rank(oct.tasks, 0.0);
  for (TaskId t = 0; t < oct.tasks; ++t) {
    double sum = 0.0;
    int n = 0;
    for (DeviceId d = 0; d < oct.devices; ++d) {
      if (!costs.can_run(t, d)) continue;
      sum += oct.at(t, d);
      ++n;
    }
    rank[t] = n > 0 ? sum / n : 0.0;
  }
  return rank;
}

}  // namespace

CostTable optimistic_cost_table(const TaskGraph& graph, const CostTable& costs, const DeviceLinks& links) {
  check_scheduling_inputs(graph, costs, links);
  return build_oct(CompactGraph(graph), costs, links);
}

Schedule schedule_peft(const TaskGraph& graph, const CostTable& costs, const DeviceLinks& links,
                       const ListOptions& options) {
  check_scheduling_inputs(graph, costs, links, options.device_ready_ms);
  const CompactGraph compact(graph);
  const CostTable oct = build_oct(compact, costs, links);
  const auto rank = oct_rank(oct, costs);

  ScheduleBuilder builder(graph, compact, costs, links, options);
  ReadyList ready(compact, rank);
  std::vector<SlotChoice> choices;
  while (!ready.empty()) {
    const TaskId task = ready.pop();
    builder.earliest_finish_all(task, choices);
    SlotChoice best = choices.front();
    double best_oeft = best.finish_ms + oct.at(task, best.device);
    for (const SlotChoice& c : choices) {
      const double oeft = c.finish_ms + oct.at(task, c.device);
      if (oeft < best_oeft || (oeft == best_oeft && c.finish_ms < best.finish_ms)) {
        best = c;
        best_oeft = oeft;
      }
    }
    builder.place(task, best);
  }
  return std::move(builder).finish();
}

}  // namespace atssim::sched
