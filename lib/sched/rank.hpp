#pragma once
// Task priorities of list scheduling (Topcuoglu 2002 §4; paper §3.3.2).
//   rank_u(i) = w̄(i) + max over successors j of (c̄(i,j) + rank_u(j))
//   rank_d(i) = max over predecessors j of (rank_d(j) + w̄(j) + c̄(j,i))
// w̄ is the mean cost over the devices that can run the task, c̄ the mean
// communication cost over ordered device pairs p ≠ q that can run the two
// ends. Unlike the paper's public code (every edge ranked at 1: makespan 91
// on the classic graph), c̄ uses the real edge weights (makespan 80).
#include <span>
#include <vector>

#include "sched/cost_table.hpp"
#include "sched/device_links.hpp"
#include "sched/task_graph.hpp"

namespace atssim::sched {

// c̄ of one edge. For uniform links this is latency + weight · ms_per_weight;
// 0 when the two ends can only run on one and the same device.
double mean_comm_ms(const Edge& edge, const CostTable& costs, const DeviceLinks& links);

std::vector<double> upward_rank(const TaskGraph& graph, const CostTable& costs,
                                const DeviceLinks& links);
// Same, reusing a topological order the caller already has.
std::vector<double> upward_rank(const TaskGraph& graph, const CostTable& costs,
                                const DeviceLinks& links, std::span<const TaskId> topo_order);

std::vector<double> downward_rank(const TaskGraph& graph, const CostTable& costs,
                                  const DeviceLinks& links);
std::vector<double> downward_rank(const TaskGraph& graph, const CostTable& costs,
                                  const DeviceLinks& links, std::span<const TaskId> topo_order);

}  // namespace atssim::sched
