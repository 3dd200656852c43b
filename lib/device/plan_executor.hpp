#pragma once
// Runs a SubstepPlan on the devices of a DeviceSet (DESIGN.md "Devices").
// Every buffer lives in SVM; the executor owns the plan. Two ways to run the
// same schedule:
//   - events: one in-order queue per device, one launch per task, event
//     waits only where the schedule says a queue must wait for another;
//   - fused: per device one launch of a dispatcher kernel per call of
//     run_substeps(), which walks the device's slots in schedule order and
//     waits through completion counters in fine-grain SVM. A wait that makes
//     no progress for ExecutorOptions::wait_timeout_s (ten times that in a
//     sanitizer build: ATSSIM_WAIT_SCALE) ends with an error.
// Both give the same bits. Knows nothing of physics.
#include <memory>
#include <span>
#include <vector>

#include "device/device_set.hpp"
#include "device/executor_choice.hpp"
#include "plan/plan_state.hpp"
#include "plan/substep_plan.hpp"
#include "plan/transfer_plan.hpp"
#include "sched/schedule.hpp"
#include "sched/task_timing.hpp"

namespace atssim::device {

enum class SvmMode { automatic, coarse, fine };

struct ExecutorOptions {
  ExecutorKind kind = ExecutorKind::automatic;  // automatic: choose_executor() on the set's devices
  SvmMode svm = SvmMode::automatic;  // events: automatic = fine grain when every device offers it; fused: fine
  std::size_t device = 0;            // the device that runs everything until a schedule is set
  std::size_t local_size = 64;       // events: fixed per kernel, pocl recompiles for each new size
  double wait_timeout_s = 10.0;  // fused: no task finished on any device for this long (×10 under sanitizers) = failure
  bool task_clock = true;        // fused: time each task with the device's cycle counter where it has one
  int never_publish = -1;        // fused, tests only: this task never reports completion
};

class PlanExecutor {
 public:
  // Checks every launch against the program's task functions (an unknown
  // function or a wrong argument list is an error naming both), builds the
  // program for every device (errors carry the build log) and uploads the
  // buffers; the plan's initial contents are released afterwards.
  PlanExecutor(const DeviceSet& devices, plan::SubstepPlan plan, ExecutorOptions options = {});
  PlanExecutor(const PlanExecutor&) = delete;
  PlanExecutor& operator=(const PlanExecutor&) = delete;
  ~PlanExecutor();

  const plan::SubstepPlan& plan() const;
  ExecutorKind kind() const;
  std::size_t device_count() const;
  // Fused only: whether tasks are timed one by one (else only launches are).
  bool has_task_clock() const;
  // Elements per work-group of its launches, one work-item each (events:
  // ExecutorOptions::local_size); 0 where each work-group runs a contiguous
  // share of a launch's range (fused).
  std::size_t work_group_elements() const;

  // Every task on one device, in topological order.
  void run_on(std::size_t device);
  // Each task on the device `schedule` gives it, each device's tasks in slot
  // order; a device waits for another only at `waits` (and, between
  // substeps, for the other devices' last task).
  void run_schedule(const sched::Schedule& schedule, std::span<const sched::Wait> waits);

  // Moves the boundaries between the parts of the (split) plan it runs to
  // `fractions` (plan::recut_plan); the schedule stays. Returns each task's
  // new share of its whole task.
  std::vector<double> recut(std::span<const double> fractions, std::size_t granule);

  // Starts `count` substeps and returns without waiting for them. With
  // `record`, the last one is timed task by task (see recorded()).
  void run_substeps(int count, bool record = false);
  // Timings of the last recorded substep, in the order the tasks ran on
  // their devices. Empty for fused execution without a task clock.
  std::vector<sched::TaskTiming> recorded();
  // Fused: each device's launch of the last run_substeps(); events: empty.
  std::vector<sched::LaunchTiming> launches();

  // Pre-profiling (paper §5): runs the plan on each device alone for
  // `substeps` substeps and reports each one's task timings to `observer`
  // (and, where tasks are timed by per-launch events inside a fused
  // executor, the launch gap), which decides what they cost
  // (sched::ProfileCosts). The state is restored afterwards; the current
  // schedule is kept. With a budget > 0, a device stops after
  // `min_substeps` once its substeps have taken `budget_ms` in all (a large
  // scene's substep takes seconds, and each timed one costs two).
  void profile(int substeps, sched::TimingObserver& observer, int min_substeps = 0, double budget_ms = 0.0);
  // Median delay from the end of work on `from` to the start of work on `to`
  // that waits for it: an event hop (events) or an SVM-atomic handshake
  // (fused).
  double measure_latency_ms(std::size_t from, std::size_t to, int repetitions = 20);

  // Devices with memories of their own (DeviceSet::memories() > 1): the
  // link between two devices (latency of a copy, ms per byte), the bytes
  // copied between memories since the last call, the copies of the last
  // recorded substep, and the plan they follow (nullptr for one memory).
  struct Link {
    double latency_ms = 0.0;
    double ms_per_byte = 0.0;  // 0 where the two share a memory
  };
  Link measure_link(std::size_t from, std::size_t to, int repetitions = 10);
  std::size_t memories() const;
  std::size_t take_bytes_moved();
  std::vector<sched::CopyTiming> copies();
  const plan::TransferPlan* transfer_plan() const;

  // Waits for everything started. Fused: throws atssim::Error (runtime)
  // naming the device and the task when a wait made no progress in time.
  void finish();

  // The state carried between substeps (waits first).
  plan::PlanState read_state();
  // The same into `into`, whose storage is reused where it has the sizes.
  void read_state(plan::PlanState& into);
  // Restores the state (the carried buffers to their initial contents when
  // it holds none) and every cache_state buffer: the caches those guard are
  // remade in the next substep from the carried buffers, as they were, so a
  // substep's result depends only on the state it starts from.
  void reset(const plan::PlanState& state);
  // The size of PlanState::carried for this plan.
  std::size_t carried_bytes() const;
  std::vector<std::byte> read(plan::BufferId id);
  void write(plan::BufferId id, std::span<const std::byte> bytes);
  // Positions as xyz float triplets (from the plan's float4 positions buffer).
  void read_positions(std::vector<float>& xyz);
  bool fine_grain() const;

  struct Impl;

 private:
  std::unique_ptr<Impl> impl_;
};

}  // namespace atssim::device
