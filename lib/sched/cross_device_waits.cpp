// Schedule::cross_device_waits — the fewest event waits that make an executor
// with one in-order queue per device respect every cross-device edge.
//
// Vector clocks: known[v][d] is the highest position on device d's queue that
// is guaranteed complete when v starts (-1: none). A task inherits the clock
// of the task before it on its own queue, then joins the clocks of the tasks
// it waits for. An input u on device p is already guaranteed when
// known[v][p] >= position(u); among the inputs that are not, one that
// happens-before another is implied by it, so only the maximal ones remain.
#include <algorithm>
#include <queue>

#include <fmt/format.h>

#include "sched/schedule.hpp"
#include "util/error.hpp"

namespace atssim::sched {

namespace {

// Tasks in an order that respects both graph edges and queue order.
std::vector<TaskId> execution_order(const Schedule& s, const TaskGraph& graph) {
  const std::size_t n = graph.size();
  std::vector<int> indegree(n, 0);
  for (TaskId v = 0; v < n; ++v) {
    indegree[v] = static_cast<int>(graph.predecessors(v).size()) + (s.placement[v].index > 0);
  }
  std::queue<TaskId> ready;
  for (TaskId v = 0; v < n; ++v) {
    if (indegree[v] == 0) ready.push(v);
  }
  std::vector<TaskId> order;
  order.reserve(n);
  while (!ready.empty()) {
    const TaskId u = ready.front();
    ready.pop();
    order.push_back(u);
    for (const Edge& e : graph.successors(u)) {
      if (--indegree[e.to] == 0) ready.push(e.to);
    }
    const Placement& p = s.placement[u];
    if (p.index + 1 < s.devices[p.device].size()) {
      const TaskId next = s.devices[p.device][p.index + 1].task;
      if (--indegree[next] == 0) ready.push(next);
    }
  }
  if (order.size() != n) {
    throw internal_error(
        "schedule: queue order contradicts the task graph (a task runs before its input "
        "on the same device); validate() the schedule first");
  }
  return order;
}

}  // namespace

std::vector<Wait> Schedule::cross_device_waits(const TaskGraph& graph) const {
  const std::size_t n = graph.size();
  const std::size_t nd = devices.size();
  if (placement.size() != n) {
    throw internal_error(fmt::format("schedule: covers {} tasks, the graph has {}", placement.size(), n));
  }
  for (TaskId t = 0; t < n; ++t) {
    if (placement[t].device >= nd) {
      throw internal_error(fmt::format("schedule: task '{}' is not scheduled", graph.task(t).name));
    }
  }
  // after[t * nd + d]: highest position on d known complete once t completes.
  std::vector<long> after(n * nd, -1);
  std::vector<Wait> waits;
  std::vector<TaskId> inputs;
  for (TaskId v : execution_order(*this, graph)) {
    const Placement pv = placement[v];
    long* known = &after[v * nd];
    if (pv.index > 0) {
      const TaskId prev = devices[pv.device][pv.index - 1].task;
      std::copy_n(&after[prev * nd], nd, known);
    }
    inputs.clear();
    for (const Edge& e : graph.predecessors(v)) {
      const Placement pu = placement[e.from];
      if (pu.device != pv.device && known[pu.device] < static_cast<long>(pu.index)) {
        inputs.push_back(e.from);
      }
    }
    // Keep an input unless another one already implies it.
    auto implies = [&](TaskId w, TaskId u) {
      const Placement pu = placement[u];
      return w != u && after[w * nd + pu.device] >= static_cast<long>(pu.index);
    };
    const std::vector<TaskId> candidates = inputs;
    for (TaskId u : candidates) {
      const bool implied = std::any_of(candidates.begin(), candidates.end(), [&](TaskId w) { return implies(w, u); });
      if (implied) continue;
      waits.push_back({u, placement[u].device, v, pv.device});
      for (std::size_t d = 0; d < nd; ++d) known[d] = std::max(known[d], after[u * nd + d]);
    }
    known[pv.device] = pv.index;
  }
  std::sort(waits.begin(), waits.end(), [&](const Wait& a, const Wait& b) {
    const Placement ca = placement[a.consumer], cb = placement[b.consumer];
    if (ca.device != cb.device) return ca.device < cb.device;
    if (ca.index != cb.index) return ca.index < cb.index;
    if (a.producer_device != b.producer_device) return a.producer_device < b.producer_device;
    return placement[a.producer].index < placement[b.producer].index;
  });
  return waits;
}

}  // namespace atssim::sched
