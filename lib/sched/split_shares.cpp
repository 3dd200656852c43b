#include "sched/split_shares.hpp"

#include <algorithm>
#include <numeric>

#include <fmt/format.h>

#include "util/error.hpp"

namespace atssim::sched {

std::vector<double> equal_fractions(std::size_t devices) {
  return std::vector<double>(devices, 1.0 / static_cast<double>(devices));
}

std::vector<double> speed_fractions(const CostTable& costs) {
  std::vector<double> speed(costs.devices, 0.0);
  for (std::size_t d = 0; d < costs.devices; ++d) {
    double total = 0.0;
    for (std::size_t t = 0; t < costs.tasks; ++t) total += costs.at(static_cast<TaskId>(t), d);
    speed[d] = 1.0 / std::max(total, 1e-9);
  }
  const double sum = std::accumulate(speed.begin(), speed.end(), 0.0);
  for (double& s : speed) s /= sum;
  return speed;
}

std::vector<DeviceId> part_devices(const TaskGraph& graph) {
  std::vector<DeviceId> device(graph.size(), 0);
  for (TaskId t = 0; t < graph.size(); ++t) device[t] = static_cast<DeviceId>(std::max(0, graph.task(t).part));
  return device;
}

CostTable costs_for_fractions(const TaskGraph& graph, const CostTable& equal_costs, std::span<const double> fractions) {
  if (graph.size() != equal_costs.tasks || fractions.size() != equal_costs.devices) {
    throw internal_error(
        fmt::format("split costs: a graph of {} tasks cut in {} parts, costs of {} tasks on {} devices", graph.size(),
                    fractions.size(), equal_costs.tasks, equal_costs.devices));
  }
  const auto n = static_cast<double>(equal_costs.devices);
  CostTable out(equal_costs.tasks, equal_costs.devices);
  for (TaskId t = 0; t < graph.size(); ++t) {
    const int part = graph.task(t).part;
    const double scale = part >= 0 ? fractions[static_cast<std::size_t>(part)] * n : 1.0;
    for (std::size_t d = 0; d < equal_costs.devices; ++d) out.at(t, d) = equal_costs.at(t, d) * scale;
  }
  return out;
}

std::vector<double> share_factors(std::span<const double> before, std::span<const double> after) {
  std::vector<double> factor(after.size(), 1.0);
  for (std::size_t t = 0; t < after.size() && t < before.size(); ++t) {
    if (before[t] > 0.0) factor[t] = after[t] / before[t];
  }
  return factor;
}

}  // namespace atssim::sched
