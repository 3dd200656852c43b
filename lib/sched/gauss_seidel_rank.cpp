#include "sched/gauss_seidel_rank.hpp"

#include <algorithm>

#include <fmt/format.h>

#include "sched/input_checks.hpp"
#include "sched/rank.hpp"
#include "util/error.hpp"

namespace atssim::sched {

namespace {

// Topological order of the graph plus the ordering chains; a cycle is an
// error that names it (via TaskGraph's own cycle detection).
std::vector<TaskId> chained_topological_order(const TaskGraph& graph, std::span<const std::vector<TaskId>> orders) {
  TaskGraph chained = graph;
  for (const auto& order : orders) {
    for (std::size_t k = 1; k < order.size(); ++k) chained.add_edge(order[k - 1], order[k], 0.0);
  }
  try {
    return chained.topological_order();
  } catch (const Error& e) {
    throw Error(std::string("Gauss-Seidel order contradicts the task graph: ") + e.what(), e.kind());
  }
}

}  // namespace

std::vector<double> gauss_seidel_rank(const TaskGraph& graph, const CostTable& costs, const DeviceLinks& links,
                                      std::span<const std::vector<TaskId>> orders) {
  check_scheduling_inputs(graph, costs, links);
  std::vector<std::vector<TaskId>> next(graph.size());
  for (const auto& order : orders) {
    for (std::size_t k = 0; k < order.size(); ++k) {
      if (order[k] >= graph.size()) {
        throw internal_error(
            fmt::format("Gauss-Seidel order names task {}, the graph has {} tasks", order[k], graph.size()));
      }
      if (k > 0) next[order[k - 1]].push_back(order[k]);
    }
  }
  const auto topo = chained_topological_order(graph, orders);
  std::vector<double> rank(graph.size(), 0.0);
  for (auto it = topo.rbegin(); it != topo.rend(); ++it) {
    const TaskId t = *it;
    double tail = 0.0;
    for (const Edge& e : graph.successors(t)) {
      tail = std::max(tail, mean_comm_ms(e, costs, links) + rank[e.to]);
    }
    for (TaskId n : next[t]) tail = std::max(tail, rank[n] + kGaussSeidelRankStep);
    rank[t] = mean_cost(costs, t) + tail;
  }
  return rank;
}

std::vector<double> gauss_seidel_rank(const TaskGraph& graph, const CostTable& costs, const DeviceLinks& links,
                                      std::span<const TaskId> order) {
  const std::vector<std::vector<TaskId>> orders{{order.begin(), order.end()}};
  return gauss_seidel_rank(graph, costs, links, orders);
}

std::vector<TaskId> gauss_seidel_order(const TaskGraph& graph, int kind) {
  std::vector<TaskId> ids;
  for (TaskId t = 0; t < graph.size(); ++t) {
    if (graph.task(t).kind == kind) ids.push_back(t);
  }
  std::stable_sort(ids.begin(), ids.end(), [&](TaskId a, TaskId b) {
    const Task& x = graph.task(a);
    const Task& y = graph.task(b);
    if (x.iteration != y.iteration) return x.iteration < y.iteration;
    return x.block != y.block ? x.block < y.block : x.part < y.part;
  });
  return ids;
}

}  // namespace atssim::sched
