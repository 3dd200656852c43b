#include "sched/profile_costs.hpp"

#include <algorithm>

#include <fmt/format.h>

#include "sched/cost_model.hpp"
#include "sched/cost_refit.hpp"
#include "util/error.hpp"

namespace atssim::sched {

ProfileCosts::ProfileCosts(std::size_t tasks, std::size_t devices, ProfileOptions options)
    : tasks_(tasks),
      devices_(devices),
      options_(options),
      substeps_(devices, 0),
      gap_ms_(devices, 0.0),
      samples_(tasks * devices) {}

void ProfileCosts::substep_alone(DeviceId device, std::span<const TaskTiming> timings) {
  if (device >= devices_) {
    throw internal_error(fmt::format("profile: a substep on device {} of {}", device, devices_));
  }
  if (substeps_[device]++ < options_.warmup) return;
  for (const Measurement& m : task_costs(timings, devices_)) {
    if (m.task >= tasks_ || m.device != device) {
      throw internal_error(fmt::format("profile: task {} timed on device {} in a substep alone on device {} ({} tasks)",
                                       m.task, m.device, device, tasks_));
    }
    samples_[m.task * devices_ + device].push_back(m.ms);
  }
}

void ProfileCosts::launch_gap(DeviceId device, double ms) {
  if (device >= devices_)
    throw internal_error(fmt::format("profile: a launch gap of device {} of {}", device, devices_));
  gap_ms_[device] = ms;
}

CostTable ProfileCosts::costs() const {
  CostTable costs(tasks_, devices_);
  for (std::size_t t = 0; t < tasks_; ++t) {
    for (std::size_t d = 0; d < devices_; ++d) {
      const std::vector<double>& s = samples_[t * devices_ + d];
      const double cost = s.empty() ? options_.floor_ms : trimmed_mean(s, options_.trim);
      costs.at(static_cast<TaskId>(t), static_cast<DeviceId>(d)) = std::max(cost - gap_ms_[d], options_.floor_ms);
    }
  }
  return costs;
}

}  // namespace atssim::sched
