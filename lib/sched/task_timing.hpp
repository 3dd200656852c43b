#pragma once
// What an executor reports about a substep it ran: plain records, no policy
// (STYLE.md: the executor observes, the cost model decides).
#include <cstddef>
#include <span>

#include "sched/ids.hpp"

namespace atssim::sched {

// One task of a recorded substep, in ms from the start of the substep's
// first task (all devices on one clock).
struct TaskTiming {
  TaskId task = 0;
  DeviceId device = 0;
  double start_ms = 0.0;
  double finish_ms = 0.0;
};

// One device's whole launch of a frame (fused execution without a task
// clock: only the launch is timed).
struct LaunchTiming {
  DeviceId device = 0;
  int substeps = 0;
  double ms = 0.0;
};

// One copy between two devices' memories in a recorded substep (devices
// that share no memory): how many bytes, and how long out and in took.
struct CopyTiming {
  DeviceId from = 0;
  DeviceId to = 0;
  std::size_t bytes = 0;
  double ms = 0.0;
};

// Receives what an executor measured while it profiles a plan (as Taskflow's
// executor reports to an ObserverInterface): the executor only reports, the
// observer (sched::ProfileCosts) decides what the numbers cost.
class TimingObserver {
 public:
  virtual ~TimingObserver() = default;
  // One substep run with every task on `device` alone, the tasks in the order
  // they ran, on one clock.
  virtual void substep_alone(DeviceId device, std::span<const TaskTiming> timings) = 0;
  // The gap the executor leaves between two launches on `device`, when its
  // timings include it (tasks timed by per-launch events); reported after
  // the device's substeps.
  virtual void launch_gap(DeviceId device, double ms) = 0;
};

}  // namespace atssim::sched
