#include "sched/cost_refit.hpp"

#include <algorithm>
#include <cmath>
#include <numeric>

#include <fmt/format.h>

#include "util/error.hpp"

namespace atssim::sched {

void refit_costs(CostTable& costs, std::span<const Measurement> measurements, const RefitOptions& options) {
  if (!(options.weight > 0.0 && options.weight <= 1.0)) {
    throw internal_error(fmt::format("cost refit: smoothing weight must be in (0, 1], got {}", options.weight));
  }
  for (const Measurement& m : measurements) {
    if (m.task >= costs.tasks || m.device >= costs.devices) {
      throw internal_error(
          fmt::format("cost refit: measurement of task {} on device {} is outside the {} × {} cost table", m.task,
                      m.device, costs.tasks, costs.devices));
    }
    if (!std::isfinite(m.ms) || m.ms < 0.0) {  // a device's clock, not atssim, went wrong
      throw Error(fmt::format("cost refit: task {} on device {} measured {} ms", m.task, m.device, m.ms),
                  ErrorKind::runtime);
    }
    double& cost = costs.at(m.task, m.device);
    if (!(cost < kCannotRun)) {
      throw internal_error(
          fmt::format("cost refit: task {} was measured on device {}, which the cost table says "
                      "cannot run it",
                      m.task, m.device));
    }
    cost += options.weight * (m.ms - cost);
  }
}

double cost_drift(const CostTable& planned, const CostTable& now) {
  if (planned.tasks != now.tasks || planned.devices != now.devices) return kCannotRun;
  double drift = 0.0;
  for (std::size_t i = 0; i < planned.ms.size(); ++i) {
    const double a = planned.ms[i];
    const double b = now.ms[i];
    const bool fa = a < kCannotRun;
    const bool fb = b < kCannotRun;
    if (fa != fb) return kCannotRun;
    if (!fa || a == b) continue;
    drift = std::max(drift, a > 0.0 ? std::abs(b - a) / a : 1.0);
  }
  return drift;
}

double trimmed_mean(std::vector<double> samples, double trim) {
  if (samples.empty()) throw internal_error("trimmed mean of no samples");
  if (!(trim >= 0.0 && trim < 0.5)) {
    throw internal_error(fmt::format("trimmed mean: trim must be in [0, 0.5), got {}", trim));
  }
  std::sort(samples.begin(), samples.end());
  const auto drop = static_cast<std::size_t>(std::floor(trim * samples.size()));
  const auto first = samples.begin() + drop;
  const auto last = samples.end() - drop;
  return std::accumulate(first, last, 0.0) / static_cast<double>(last - first);
}

}  // namespace atssim::sched
