#pragma once
// Runs a solver's SubstepPlan on the devices of a DeviceSet: every buffer in
// SVM, one OpenCL kernel object per launch with its arguments set once, one
// in-order queue per device, and event waits only where a schedule says a
// queue must wait for another (DESIGN.md "Devices"). Knows nothing of physics.
#include <memory>
#include <span>
#include <vector>

#include "device/device_set.hpp"
#include "sched/cost_table.hpp"
#include "sched/schedule.hpp"
#include "solver/substep_plan.hpp"

namespace atssim::device {

enum class SvmMode { automatic, coarse, fine };

struct ExecutorOptions {
  SvmMode svm = SvmMode::automatic;  // automatic: fine grain when every device offers it
  std::size_t device = 0;            // the device that runs everything until a schedule is set
  std::size_t local_size = 64;       // fixed per kernel: pocl recompiles for each new size
};

// Measured times of one task in a recorded substep, in ms from the start of
// the substep's first task (all devices share one clock: OpenCL profiling).
struct TaskTiming {
  sched::TaskId task = 0;
  std::size_t device = 0;
  double start_ms = 0.0;
  double finish_ms = 0.0;
};

class PlanExecutor {
 public:
  // Builds the plan's program for every device (errors carry the build log)
  // and uploads the buffers' initial contents.
  PlanExecutor(const DeviceSet& devices, const solver::SubstepPlan& plan, ExecutorOptions options = {});
  PlanExecutor(const PlanExecutor&) = delete;
  PlanExecutor& operator=(const PlanExecutor&) = delete;
  ~PlanExecutor();

  std::size_t device_count() const;

  // Every task on one device, in topological order.
  void run_on(std::size_t device);
  // Each task on the device `schedule` gives it, each device's tasks in slot
  // order; a queue waits for another only at `waits` (and, between
  // substeps, for the other queues' last task).
  void run_schedule(const sched::Schedule& schedule, std::span<const sched::Wait> waits);

  // Enqueues `count` substeps and returns without waiting. With `record`,
  // the last one is timed task by task (see recorded()).
  void enqueue_substeps(int count, bool record = false);
  // Timings of the last recorded substep, in task order of execution (waits).
  std::vector<TaskTiming> recorded();

  // Pre-profiling (paper §5): runs the plan on each device alone for
  // `repetitions` substeps after one warm-up, and returns the trimmed mean of
  // each task's cost there, including the queue's launch gap. Simulation
  // state is restored afterwards; the current schedule is kept.
  sched::CostTable profile(int repetitions = 5);
  // Median time from the end of a task on `from` to the start of a task on
  // `to` that waits for it (an event hop), over `repetitions` hops.
  double measure_latency_ms(std::size_t from, std::size_t to, int repetitions = 20);

  // Waits for everything enqueued.
  void finish();
  // Copies a buffer to the host (waits first).
  std::vector<std::byte> read(solver::BufferId id);
  void write(solver::BufferId id, std::span<const std::byte> bytes);
  // Positions as xyz float triplets (from the plan's float4 position buffer).
  void read_positions(std::vector<float>& xyz);
  bool fine_grain() const;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace atssim::device
