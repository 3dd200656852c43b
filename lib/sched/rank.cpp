#include "sched/rank.hpp"

#include <algorithm>

namespace atssim::sched {

double mean_comm_ms(const Edge& edge, const CostTable& costs, const DeviceLinks& links) {
  double sum = 0.0;
  int pairs = 0;
  for (DeviceId p = 0; p < costs.devices; ++p) {
    if (!costs.can_run(edge.from, p)) continue;
    for (DeviceId q = 0; q < costs.devices; ++q) {
      if (q == p || !costs.can_run(edge.to, q)) continue;
      sum += links.comm_ms(edge.comm, p, q);
      ++pairs;
    }
  }
  return pairs > 0 ? sum / pairs : 0.0;
}

std::vector<double> upward_rank(const TaskGraph& graph, const CostTable& costs,
                                const DeviceLinks& links) {
  const auto order = graph.topological_order();
  return upward_rank(graph, costs, links, order);
}

std::vector<double> upward_rank(const TaskGraph& graph, const CostTable& costs,
                                const DeviceLinks& links, std::span<const TaskId> topo_order) {
  std::vector<double> rank(graph.size(), 0.0);
  for (auto it = topo_order.rbegin(); it != topo_order.rend(); ++it) {
    double tail = 0.0;
    for (const Edge& e : graph.successors(*it)) {
      tail = std::max(tail, mean_comm_ms(e, costs, links) + rank[e.to]);
    }
    rank[*it] = mean_cost(costs, *it) + tail;
  }
  return rank;
}

std::vector<double> downward_rank(const TaskGraph& graph, const CostTable& costs,
                                  const DeviceLinks& links) {
  const auto order = graph.topological_order();
  return downward_rank(graph, costs, links, order);
}

std::vector<double> downward_rank(const TaskGraph& graph, const CostTable& costs,
                                  const DeviceLinks& links, std::span<const TaskId> topo_order) {
  std::vector<double> rank(graph.size(), 0.0);
  for (TaskId id : topo_order) {
    double head = 0.0;
    for (const Edge& e : graph.predecessors(id)) {
      head = std::max(head, rank[e.from] + mean_cost(costs, e.from) + mean_comm_ms(e, costs, links));
    }
    rank[id] = head;
  }
  return rank;
}

}  // namespace atssim::sched
