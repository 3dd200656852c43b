#pragma once
// The fused executor (internal to lib/device; DESIGN.md "Devices"): for a
// set whose devices share one memory (one context), per
// device one launch of the program's dispatcher (kernels/device/dispatch.cl)
// per run, which walks the device's slots for every substep and waits
// through completion counters in fine-grain SVM. The host only starts the
// launches and watches their progress: a run in which no slot finishes on
// any device for `wait_timeout_s` (ten times that in a sanitizer build:
// ATSSIM_WAIT_SCALE) is aborted through an SVM flag and reported, never
// left hanging.
#include <memory>
#include <vector>

#include "device/executor_parts.hpp"
#include "device/svm_arena.hpp"
#include "sched/task_timing.hpp"

namespace atssim::device {

struct FusedOptions {
  double wait_timeout_s = 10.0;  // times ATSSIM_WAIT_SCALE (10) in a sanitizer build
  bool task_clock = true;        // stamp tasks where the device has a cycle counter
  int never_publish = -1;        // tests: this task never reports completion
};

class FusedRunner {
 public:
  // `arena` must be fine-grain with atomics (its counters and records live
  // there). Throws atssim::Error (runtime) when the devices do not run their
  // work-groups, or each other, at the same time (a probe that times out).
  FusedRunner(const PlanResources& resources, SvmArena& arena, const FusedOptions& options);
  FusedRunner(const FusedRunner&) = delete;
  FusedRunner& operator=(const FusedRunner&) = delete;
  ~FusedRunner();

  bool has_clock() const;
  void set_steps(const std::vector<Step>& steps);
  // Starts one dispatcher launch per device that has slots, for `count`
  // substeps; with `record`, the last substep's tasks are stamped.
  void start(int count, bool record);
  void finish();
  std::vector<sched::TaskTiming> timings();
  std::vector<sched::LaunchTiming> launches();
  double latency_ms(std::size_t from, std::size_t to, int repetitions);

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

// Whether the devices run together what the dispatcher needs: every
// work-group of each device at once, and every pair of devices at once.
// Returns "" when they do, else what failed (each probe gives up after
// `timeout_s`).
std::string check_concurrency(const DeviceSet::Impl& set, SvmArena& arena, double timeout_s);

}  // namespace atssim::device
