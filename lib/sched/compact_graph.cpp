#include "sched/compact_graph.hpp"

namespace atssim::sched {

CompactGraph::CompactGraph(const TaskGraph& graph) {
  const std::size_t n = graph.size();
  succ_begin_.assign(n + 1, 0);
  pred_begin_.assign(n + 1, 0);
  for (TaskId t = 0; t < n; ++t) {
    succ_begin_[t + 1] = succ_begin_[t] + static_cast<std::uint32_t>(graph.successors(t).size());
    pred_begin_[t + 1] = pred_begin_[t] + static_cast<std::uint32_t>(graph.predecessors(t).size());
  }
  succ_.resize(succ_begin_[n]);
  pred_.resize(pred_begin_[n]);
  for (TaskId t = 0; t < n; ++t) {
    std::uint32_t i = succ_begin_[t];
    for (const Edge& e : graph.successors(t)) succ_[i++] = {e.to, e.comm};
    i = pred_begin_[t];
    for (const Edge& e : graph.predecessors(t)) pred_[i++] = {e.from, e.comm};
  }

  std::vector<std::uint32_t> waiting(n);
  topo_.reserve(n);
  for (TaskId t = 0; t < n; ++t) {
    waiting[t] = pred_begin_[t + 1] - pred_begin_[t];
    if (waiting[t] == 0) topo_.push_back(t);
  }
  for (std::size_t head = 0; head < topo_.size(); ++head) {
    for (const CompactEdge& e : successors(topo_[head])) {
      if (--waiting[e.task] == 0) topo_.push_back(e.task);
    }
  }
  if (topo_.size() != n) graph.topological_order();  // throws, naming the cycle
}

}  // namespace atssim::sched
