#include "sched/input_checks.hpp"

#include <cmath>

#include <fmt/format.h>

#include "util/error.hpp"

namespace atssim::sched {

void check_scheduling_inputs(const TaskGraph& graph, const CostTable& costs, const DeviceLinks& links,
                             std::span<const double> device_ready_ms) {
  if (costs.tasks != graph.size()) {
    throw internal_error(
        fmt::format("scheduler: the cost table has {} tasks, the task graph {}", costs.tasks, graph.size()));
  }
  if (costs.devices == 0) throw internal_error("scheduler: the cost table has no device");
  if (links.devices != costs.devices || links.latency_ms.size() != links.devices * links.devices ||
      links.ms_per_weight.size() != links.devices * links.devices) {
    throw internal_error(
        fmt::format("scheduler: the cost table has {} devices, the device links {}", costs.devices, links.devices));
  }
  for (TaskId t = 0; t < costs.tasks; ++t) {
    bool runs_somewhere = false;
    for (DeviceId d = 0; d < costs.devices; ++d) {
      const double c = costs.at(t, d);
      if (std::isnan(c) || c < 0.0) {
        throw internal_error(
            fmt::format("scheduler: task '{}' has cost {} on device {}; costs must be "
                        ">= 0 ms (or inf = cannot run)",
                        graph.task(t).name, c, d));
      }
      runs_somewhere = runs_somewhere || c < kCannotRun;
    }
    if (!runs_somewhere) {
      throw internal_error(
          fmt::format("scheduler: task '{}' cannot run on any device (all costs are inf)", graph.task(t).name));
    }
    for (const Edge& e : graph.successors(t)) {
      if (!std::isfinite(e.comm) || e.comm < 0.0) {
        throw internal_error(
            fmt::format("scheduler: edge '{}' -> '{}' has weight {}; weights must be "
                        "finite and >= 0",
                        graph.task(e.from).name, graph.task(e.to).name, e.comm));
      }
    }
  }
  for (std::size_t i = 0; i < links.latency_ms.size(); ++i) {
    const double l = links.latency_ms[i];
    const double w = links.ms_per_weight[i];
    if (!std::isfinite(l) || l < 0.0 || !std::isfinite(w) || w < 0.0) {
      throw internal_error(
          fmt::format("scheduler: link {} -> {} has latency {} ms and {} ms per weight; "
                      "both must be finite and >= 0",
                      i / links.devices, i % links.devices, l, w));
    }
  }
  if (!device_ready_ms.empty()) {
    if (device_ready_ms.size() != costs.devices) {
      throw internal_error(
          fmt::format("scheduler: {} device ready times given for {} devices", device_ready_ms.size(), costs.devices));
    }
    for (double t0 : device_ready_ms) {
      if (!std::isfinite(t0)) throw internal_error("scheduler: a device ready time is not finite");
    }
  }
}

}  // namespace atssim::sched
