#pragma once
// Pre-profiling (paper §5): the executor runs the plan on each device alone
// and reports the timings (sched::TimingObserver); this turns them into the
// cost table the first schedule is made with. Pure: timings in, table out.
#include <vector>

#include "sched/cost_table.hpp"
#include "sched/task_timing.hpp"

namespace atssim::sched {

struct ProfileOptions {
  int warmup = 1;          // substeps per device left out first (their launches may compile)
  double trim = 0.2;       // trimmed mean: the fraction dropped at each end (sched::trimmed_mean)
  double floor_ms = 1e-6;  // no task costs less (a cost of 0 would make a device look free)
  // How long to profile: at least min_timed substeps per device after the
  // warm-up; more, up to the caller's count, while a device's profile has
  // taken under budget_ms (a paper-size dress's substep takes ~1.8 s).
  int min_timed = 2;
  double budget_ms = 1000.0;
};

// A task costs its device what sched::task_costs attributes to it in each
// substep (from the end of the task before it to its own end), as the
// trimmed mean over the substeps after the warm-up, less the device's launch
// gap where the executor reported one, and at least floor_ms.
class ProfileCosts final : public TimingObserver {
 public:
  ProfileCosts(std::size_t tasks, std::size_t devices, ProfileOptions options = {});

  void substep_alone(DeviceId device, std::span<const TaskTiming> timings) override;
  void launch_gap(DeviceId device, double ms) override;

  CostTable costs() const;

 private:
  std::size_t tasks_, devices_;
  ProfileOptions options_;
  std::vector<int> substeps_;                 // per device, reported so far
  std::vector<double> gap_ms_;                // per device
  std::vector<std::vector<double>> samples_;  // [task * devices + device]
};

}  // namespace atssim::sched
