#include "sched/cost_model.hpp"

#include <algorithm>
#include <cmath>

namespace atssim::sched {

std::vector<Measurement> task_costs(std::span<const TaskTiming> timings, std::size_t devices,
                                    std::span<const Wait> waits) {
  std::vector<TaskId> waited;
  for (const Wait& w : waits) waited.push_back(w.consumer);
  std::sort(waited.begin(), waited.end());
  std::vector<double> device_end(devices, -1.0);  // -1: no task ran there yet
  std::vector<Measurement> out;
  for (const TaskTiming& t : timings) {
    const double previous = device_end.at(t.device);
    const bool waits_for_other = std::binary_search(waited.begin(), waited.end(), t.task);
    const double from = previous < 0.0 || waits_for_other ? std::max(t.start_ms, previous) : previous;
    device_end[t.device] = t.finish_ms;
    out.push_back({t.task, t.device, std::max(t.finish_ms - from, 1e-6)});
  }
  return out;
}

double total_drift(const CostTable& planned, const CostTable& now) {
  double worst = 0.0;
  for (std::size_t d = 0; d < planned.devices; ++d) {
    double a = 0.0, b = 0.0;
    for (std::size_t t = 0; t < planned.tasks; ++t) {
      const double pa = planned.at(static_cast<TaskId>(t), d), pb = now.at(static_cast<TaskId>(t), d);
      if (pa < kCannotRun) a += pa;
      if (pb < kCannotRun) b += pb;
    }
    if (a > 0.0) worst = std::max(worst, std::abs(b - a) / a);
  }
  return worst;
}

double link_drift(const DeviceLinks& planned, const DeviceLinks& now) {
  double worst = 0.0;
  const std::size_t n = std::min(planned.ms_per_weight.size(), now.ms_per_weight.size());
  for (std::size_t i = 0; i < n; ++i) {
    const double a = planned.ms_per_weight[i];
    if (a > 0.0) worst = std::max(worst, std::abs(now.ms_per_weight[i] - a) / a);
  }
  return worst;
}

void refit_latency(DeviceLinks& links, std::span<const TaskTiming> timings, std::span<const Wait> waits,
                   std::size_t task_count, double weight) {
  if (waits.empty()) return;
  const std::size_t n = links.devices;
  std::vector<const TaskTiming*> of_task(task_count, nullptr);
  std::vector<double> device_free(task_count, 0.0);  // when the task's device was free for it
  std::vector<double> last_end(n, 0.0);
  for (const TaskTiming& t : timings) {
    of_task.at(t.task) = &t;
    device_free[t.task] = last_end.at(t.device);
    last_end[t.device] = t.finish_ms;
  }
  std::vector<std::vector<double>> samples(n * n);
  for (const Wait& w : waits) {
    const TaskTiming* p = of_task.at(w.producer);
    const TaskTiming* c = of_task.at(w.consumer);
    if (p == nullptr || c == nullptr || p->finish_ms < device_free[w.consumer]) continue;
    samples[w.producer_device * n + w.consumer_device].push_back(std::max(c->start_ms - p->finish_ms, 0.0));
  }
  for (std::size_t a = 0; a < n; ++a) {
    for (std::size_t b = 0; b < n; ++b) {
      auto& s = samples[a * n + b];
      if (a == b || s.size() < 3) continue;
      std::nth_element(s.begin(), s.begin() + s.size() / 2, s.end());
      double& latency = links.latency_ms[a * n + b];
      latency += weight * (s[s.size() / 2] - latency);
    }
  }
}

void refit_from_launches(CostTable& costs, const Schedule& predicted, std::span<const LaunchTiming> launches,
                         double weight) {
  for (const LaunchTiming& l : launches) {
    if (l.device >= predicted.devices.size() || predicted.devices[l.device].empty() || l.substeps <= 0) continue;
    const double predicted_end = predicted.devices[l.device].back().finish_ms;
    if (!(predicted_end > 0.0)) continue;
    const double scale = 1.0 + weight * (l.ms / l.substeps / predicted_end - 1.0);
    for (const Slot& s : predicted.devices[l.device]) {
      double& c = costs.at(s.task, l.device);
      if (c < kCannotRun) c *= scale;
    }
  }
}

std::vector<double> balanced_fractions(const CostTable& costs, std::span<const DeviceId> assignment,
                                       std::span<const double> fractions, double tolerance) {
  std::vector<double> busy(fractions.size(), 0.0);
  for (TaskId t = 0; t < assignment.size(); ++t) {
    if (assignment[t] < busy.size() && costs.at(t, assignment[t]) < kCannotRun)
      busy[assignment[t]] += costs.at(t, assignment[t]);
  }
  const auto [lo, hi] = std::minmax_element(busy.begin(), busy.end());
  if (*lo <= 0.0 || *hi / *lo - 1.0 <= tolerance) return {fractions.begin(), fractions.end()};
  std::vector<double> out(fractions.size());
  double sum = 0.0;
  for (std::size_t d = 0; d < out.size(); ++d) sum += out[d] = fractions[d] / busy[d];
  for (double& f : out) f /= sum;
  return out;
}

double measured_makespan_ms(std::span<const TaskTiming> timings, std::span<const LaunchTiming> launches) {
  double makespan = 0.0;
  for (const TaskTiming& t : timings) makespan = std::max(makespan, t.finish_ms);
  if (timings.empty()) {
    for (const LaunchTiming& l : launches) makespan = std::max(makespan, l.ms / std::max(1, l.substeps));
  }
  return makespan;
}

void CostModel::rescale(std::span<const double> factor) {
  for (TaskId t = 0; t < costs_.tasks && t < factor.size(); ++t) {
    for (DeviceId d = 0; d < costs_.devices; ++d) {
      if (costs_.at(t, d) < kCannotRun) costs_.at(t, d) *= factor[t];
      if (planned_.at(t, d) < kCannotRun) planned_.at(t, d) *= factor[t];
    }
  }
}

CostModel::CostModel(CostTable profiled, DeviceLinks links, double drift_threshold)
    : profiled_(profiled),
      costs_(profiled),
      planned_(std::move(profiled)),
      links_(links),
      planned_links_(std::move(links)),
      threshold_(drift_threshold) {}

void CostModel::observe(std::span<const TaskTiming> timings, std::span<const Wait> waits) {
  const std::vector<Measurement> measured = task_costs(timings, costs_.devices, waits);
  refit_costs(costs_, measured);
  refit_latency(links_, timings, waits, costs_.tasks);
}

void CostModel::observe_copies(std::span<const CopyTiming> copies) {
  const std::size_t n = links_.devices;
  std::vector<double> bytes(n * n, 0.0), ms(n * n, 0.0), count(n * n, 0.0);
  for (const CopyTiming& c : copies) {
    if (c.from >= n || c.to >= n || c.bytes == 0) continue;
    bytes[c.from * n + c.to] += static_cast<double>(c.bytes);
    ms[c.from * n + c.to] += c.ms;
    count[c.from * n + c.to] += 1.0;
  }
  for (std::size_t i = 0; i < n * n; ++i) {
    if (bytes[i] <= 0.0 || links_.ms_per_weight[i] <= 0.0) continue;
    // Each copy's time includes the link's latency: what remains is per byte.
    const double per_byte = std::max(ms[i] - count[i] * links_.latency_ms[i], 0.0) / bytes[i];
    links_.ms_per_weight[i] += 0.5 * (per_byte - links_.ms_per_weight[i]);
  }
}

void CostModel::observe_launches(const Schedule& predicted, std::span<const LaunchTiming> launches) {
  refit_from_launches(costs_, predicted, launches);
}

void CostModel::observe_frame(std::span<const TaskTiming> timings, std::span<const Wait> waits,
                              std::span<const CopyTiming> copies, const Schedule& predicted,
                              std::span<const LaunchTiming> launches) {
  if (!timings.empty()) {
    observe(timings, waits);
    observe_copies(copies);
  } else {
    observe_launches(predicted, launches);
  }
}

bool CostModel::drifted() const {
  return total_drift(planned_, costs_) > threshold_ || link_drift(planned_links_, links_) > threshold_;
}

void CostModel::plan_made() {
  planned_ = costs_;
  planned_links_ = links_;
}

}  // namespace atssim::sched
