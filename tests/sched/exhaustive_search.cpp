#include "exhaustive_search.hpp"

#include <algorithm>
#include <cstdint>
#include <limits>
#include <stdexcept>
#include <vector>

namespace atssim::sched::test {

namespace {

struct Search {
  const TaskGraph& graph;
  const CostTable& costs;
  const DeviceLinks& links;
  std::size_t n;
  std::size_t nd;
  std::vector<double> tail;  // min-cost path from a task to an exit, task included
  std::vector<double> device_free;
  std::vector<double> finish;
  std::vector<DeviceId> device;
  double best;

  void run(std::uint32_t placed, double last_start, double makespan) {
    if (placed == (1u << n) - 1) {
      best = std::min(best, makespan);
      return;
    }
    double bound = makespan;
    for (TaskId t = 0; t < n; ++t) {
      if (!(placed >> t & 1)) bound = std::max(bound, last_start + tail[t]);
    }
    if (bound >= best) return;
    for (TaskId t = 0; t < n; ++t) {
      if (placed >> t & 1) continue;
      bool ready = true;
      for (const Edge& e : graph.predecessors(t)) ready = ready && (placed >> e.from & 1);
      if (!ready) continue;
      for (DeviceId d = 0; d < nd; ++d) {
        const double cost = costs.at(t, d);
        if (!(cost < kCannotRun)) continue;
        double start = device_free[d];
        for (const Edge& e : graph.predecessors(t)) {
          start = std::max(start, finish[e.from] + links.comm_ms(e.comm, device[e.from], d));
        }
        if (start < last_start) continue;  // not in canonical (start-time) order
        const double saved_free = device_free[d];
        device_free[d] = start + cost;
        finish[t] = start + cost;
        device[t] = d;
        run(placed | 1u << t, start, std::max(makespan, start + cost));
        device_free[d] = saved_free;
      }
    }
  }
};

}  // namespace

double optimal_makespan(const TaskGraph& graph, const CostTable& costs, const DeviceLinks& links,
                        std::span<const double> device_ready_ms) {
  const std::size_t n = graph.size();
  if (n > 12) throw std::invalid_argument("exhaustive search is for tiny graphs");
  Search s{graph,
           costs,
           links,
           n,
           costs.devices,
           std::vector<double>(n, 0.0),
           std::vector<double>(costs.devices, 0.0),
           std::vector<double>(n, 0.0),
           std::vector<DeviceId>(n, 0),
           std::numeric_limits<double>::infinity()};
  if (!device_ready_ms.empty()) s.device_free.assign(device_ready_ms.begin(), device_ready_ms.end());
  const auto topo = graph.topological_order();
  for (auto it = topo.rbegin(); it != topo.rend(); ++it) {
    double after = 0.0;
    for (const Edge& e : graph.successors(*it)) after = std::max(after, s.tail[e.to]);
    s.tail[*it] = min_cost(costs, *it) + after;
  }
  s.run(0, -kCannotRun, 0.0);
  return s.best;
}

}  // namespace atssim::sched::test
