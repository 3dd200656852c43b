#include "sched/lower_bound.hpp"

#include <algorithm>

namespace atssim::sched {

double critical_path_bound(const TaskGraph& graph, const CostTable& costs) {
  std::vector<double> finish(graph.size(), 0.0);
  double longest = 0.0;
  for (TaskId t : graph.topological_order()) {
    double start = 0.0;
    for (const Edge& e : graph.predecessors(t)) start = std::max(start, finish[e.from]);
    finish[t] = start + min_cost(costs, t);
    longest = std::max(longest, finish[t]);
  }
  return longest;
}

double work_bound(const CostTable& costs) {
  if (costs.devices == 0) return 0.0;
  double sum = 0.0;
  for (TaskId t = 0; t < costs.tasks; ++t) sum += min_cost(costs, t);
  return sum / static_cast<double>(costs.devices);
}

double makespan_lower_bound(const TaskGraph& graph, const CostTable& costs) {
  return std::max(critical_path_bound(graph, costs), work_bound(costs));
}

}  // namespace atssim::sched
