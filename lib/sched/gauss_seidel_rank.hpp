#pragma once
// Gauss-Seidel rank_u (paper §4.1.2, Fig. 9). Plain rank_u lets a block of a
// later iteration outrank a block of an earlier one (its remaining path is
// longer), so HEFT interleaves iterations and breaks the Gauss-Seidel order.
// Rule: compute rank_u over the task graph *plus* each given order as a chain
// of ordering edges (no data, no communication), each adding 1e-6 ms:
//   rank(i) = w̄(i) + max( max over data successors j (c̄(i,j) + rank(j)),
//                         rank(next of i in an order) + 1e-6 )
// Along every order the ranks then strictly decrease, every task still
// outranks its successors, and HEFT's ready list takes the blocks in order.
// An order that contradicts the graph is an error naming the cycle.
#include <span>
#include <string_view>
#include <vector>

#include "sched/cost_table.hpp"
#include "sched/device_links.hpp"
#include "sched/task_graph.hpp"

namespace atssim::sched {

inline constexpr double kGaussSeidelRankStep = 1e-6;  // ms; far below any measured cost

std::vector<double> gauss_seidel_rank(const TaskGraph& graph, const CostTable& costs, const DeviceLinks& links,
                                      std::span<const std::vector<TaskId>> orders);

// Convenience: one order.
std::vector<double> gauss_seidel_rank(const TaskGraph& graph, const CostTable& costs, const DeviceLinks& links,
                                      std::span<const TaskId> order);

// The tasks of `kind` in Gauss-Seidel order: by iteration, then block, then id.
std::vector<TaskId> gauss_seidel_order(const TaskGraph& graph, int kind);

}  // namespace atssim::sched
