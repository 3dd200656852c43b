#pragma once
// Task priorities of list scheduling (Topcuoglu 2002 §4; paper §3.3.2).
//   rank_u(i) = w̄(i) + max over successors j of (c̄(i,j) + rank_u(j))
//   rank_d(i) = max over predecessors j of (rank_d(j) + w̄(j) + c̄(j,i))
// w̄ is the mean cost over the devices that can run the task, c̄ the mean
// communication cost over ordered device pairs p ≠ q that can run the two
// ends. Unlike the paper's public code (every edge ranked at 1: makespan 91
// on the classic graph), c̄ uses the real edge weights (makespan 80).
#include <vector>

#include "sched/compact_graph.hpp"
#include "sched/cost_table.hpp"
#include "sched/device_links.hpp"
#include "sched/task_graph.hpp"

namespace atssim::sched {

// c̄ of one edge. For uniform links this is latency + weight · ms_per_weight;
// 0 when the two ends can only run on one and the same device.
double mean_comm_ms(const Edge& edge, const CostTable& costs, const DeviceLinks& links);

// c̄ for many edges: the mean latency and ms-per-weight over all device
// pairs are computed once and used whenever both ends run everywhere.
class MeanComm {
 public:
  MeanComm(const CostTable& costs, const DeviceLinks& links);
  double operator()(TaskId from, TaskId to, double weight) const;

 private:
  const CostTable& costs_;
  const DeviceLinks& links_;
  std::vector<bool> runs_everywhere_;
  double latency_ = 0.0;
  double per_weight_ = 0.0;
};

std::vector<double> upward_rank(const TaskGraph& graph, const CostTable& costs, const DeviceLinks& links);
std::vector<double> upward_rank(const CompactGraph& graph, const CostTable& costs, const DeviceLinks& links);

std::vector<double> downward_rank(const TaskGraph& graph, const CostTable& costs, const DeviceLinks& links);
std::vector<double> downward_rank(const CompactGraph& graph, const CostTable& costs, const DeviceLinks& links);

}  // namespace atssim::sched
