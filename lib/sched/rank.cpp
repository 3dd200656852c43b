#include "sched/rank.hpp"

#include <algorithm>

namespace atssim::sched {

namespace {

double mean_comm_general(TaskId from, TaskId to, double weight, const CostTable& costs, const DeviceLinks& links) {
  double sum = 0.0;
  int pairs = 0;
  for (DeviceId p = 0; p < costs.devices; ++p) {
    if (!costs.can_run(from, p)) continue;
    for (DeviceId q = 0; q < costs.devices; ++q) {
      if (q == p || !costs.can_run(to, q)) continue;
      sum += links.comm_ms(weight, p, q);
      ++pairs;
    }
  }
  return pairs > 0 ? sum / pairs : 0.0;
}

std::vector<double> mean_costs(const CostTable& costs) {
  std::vector<double> mean(costs.tasks);
  for (TaskId t = 0; t < costs.tasks; ++t) mean[t] = mean_cost(costs, t);
  return mean;
}

}  // namespace

double mean_comm_ms(const Edge& edge, const CostTable& costs, const DeviceLinks& links) {
  return mean_comm_general(edge.from, edge.to, edge.comm, costs, links);
}

MeanComm::MeanComm(const CostTable& costs, const DeviceLinks& links)
    : costs_(costs), links_(links), runs_everywhere_(costs.tasks, true) {
  for (TaskId t = 0; t < costs.tasks; ++t) {
    for (DeviceId d = 0; d < costs.devices; ++d) {
      if (!costs.can_run(t, d)) runs_everywhere_[t] = false;
    }
  }
  const std::size_t nd = links.devices;
  if (nd < 2) return;
  for (DeviceId p = 0; p < nd; ++p) {
    for (DeviceId q = 0; q < nd; ++q) {
      if (p == q) continue;
      latency_ += links.latency_ms[p * nd + q];
      per_weight_ += links.ms_per_weight[p * nd + q];
    }
  }
  const double pairs = static_cast<double>(nd * (nd - 1));
  latency_ /= pairs;
  per_weight_ /= pairs;
}

double MeanComm::operator()(TaskId from, TaskId to, double weight) const {
  if (runs_everywhere_[from] && runs_everywhere_[to]) {
    return costs_.devices < 2 ? 0.0 : latency_ + weight * per_weight_;
  }
  return mean_comm_general(from, to, weight, costs_, links_);
}

std::vector<double> upward_rank(const TaskGraph& graph, const CostTable& costs, const DeviceLinks& links) {
  return upward_rank(CompactGraph(graph), costs, links);
}

std::vector<double> upward_rank(const CompactGraph& graph, const CostTable& costs, const DeviceLinks& links) {
  const MeanComm comm(costs, links);
  const auto topo = graph.topological_order();
  std::vector<double> rank = mean_costs(costs);
  for (auto it = topo.rbegin(); it != topo.rend(); ++it) {
    double tail = 0.0;
    for (const CompactEdge& e : graph.successors(*it)) {
      tail = std::max(tail, comm(*it, e.task, e.comm) + rank[e.task]);
    }
    rank[*it] += tail;
  }
  return rank;
}

std::vector<double> downward_rank(const TaskGraph& graph, const CostTable& costs, const DeviceLinks& links) {
  return downward_rank(CompactGraph(graph), costs, links);
}

std::vector<double> downward_rank(const CompactGraph& graph, const CostTable& costs, const DeviceLinks& links) {
  const MeanComm comm(costs, links);
  const auto mean = mean_costs(costs);
  std::vector<double> rank(graph.size(), 0.0);
  for (TaskId id : graph.topological_order()) {
    double head = 0.0;
    for (const CompactEdge& e : graph.predecessors(id)) {
      head = std::max(head, rank[e.task] + mean[e.task] + comm(e.task, id, e.comm));
    }
    rank[id] = head;
  }
  return rank;
}

}  // namespace atssim::sched
