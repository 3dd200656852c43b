#include "plan/async_placement.hpp"

#include <algorithm>
#include <vector>

#include <fmt/format.h>

#include "plan/task_kind.hpp"
#include "sched/gauss_seidel_rank.hpp"
#include "sched/heft.hpp"
#include "util/error.hpp"

namespace atssim::plan {

AsyncPlacement place_async(const SubstepPlan& relaxed, sched::CostTable costs, const sched::DeviceLinks& hop,
                           bool latest) {
  const sched::TaskGraph& graph = relaxed.graph;
  const std::size_t n = costs.devices;
  if (costs.tasks != graph.size() || hop.devices != n) {
    throw internal_error(
        fmt::format("async placement: costs of {} tasks on {} devices and links of {}, the plan has {} tasks",
                    costs.tasks, n, hop.devices, graph.size()));
  }
  AsyncPlacement out;
  std::vector<double> total(n, 0.0);
  for (sched::TaskId t = 0; t < graph.size(); ++t) {
    for (std::size_t d = 0; d < n; ++d) total[d] += costs.at(t, d);
  }
  out.main_device = static_cast<sched::DeviceId>(std::min_element(total.begin(), total.end()) - total.begin());
  sched::TaskId predict = 0;
  for (sched::TaskId t = 0; t < graph.size(); ++t) {
    if (graph.task(t).iteration >= 0) continue;
    if (kind_of(graph.task(t)) == TaskKind::predict) predict = t;
    for (std::size_t d = 0; d < n; ++d) {
      if (d != out.main_device) costs.at(t, d) = sched::kCannotRun;
    }
  }
  sched::DeviceLinks links = hop;
  for (std::size_t i = 0; i < links.latency_ms.size(); ++i) {
    if (i % (n + 1) != 0) links.latency_ms[i] += 2.0 * costs.at(predict, out.main_device);
  }
  std::vector<int> kinds;  // the Gauss-Seidel kinds, in order of first appearance
  for (const sched::Task& t : graph.tasks()) {
    if (traits(kind_of(t)).gauss_seidel && std::find(kinds.begin(), kinds.end(), t.kind) == kinds.end()) {
      kinds.push_back(t.kind);
    }
  }
  std::vector<std::vector<sched::TaskId>> orders;
  for (int kind : kinds) orders.push_back(sched::gauss_seidel_order(graph, kind));
  sched::HeftOptions heft;
  heft.priority = sched::gauss_seidel_rank(graph, costs, links, orders);
  out.placed = sched::schedule_heft(graph, costs, links, heft);
  out.map = sched::build_sync_map(graph, out.placed, hop, out.main_device, {latest});
  return out;
}

}  // namespace atssim::plan
