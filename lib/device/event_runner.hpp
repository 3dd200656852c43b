#pragma once
// The events executor (internal to lib/device): one in-order profiling
// queue per device, one kernel launch per task launch (the task function's
// thin kernel ats_k_<name>), event waits only at cross-device edges
// (DESIGN.md "Devices": the reference way of running a plan). Devices with
// memories of their own wait for each other through the copies of
// MemoryCopies instead.
#include <memory>
#include <vector>

#include "device/executor_parts.hpp"
#include "sched/task_timing.hpp"

namespace atssim::device {

class EventRunner {
 public:
  EventRunner(const PlanResources& resources, std::size_t local_size);
  EventRunner(const EventRunner&) = delete;
  EventRunner& operator=(const EventRunner&) = delete;
  ~EventRunner();

  void set_steps(const std::vector<Step>& steps);
  // Enqueues `count` substeps; with `record` the last is timed per task.
  void enqueue(int count, bool record);
  std::vector<sched::TaskTiming> timings();
  void finish();
  double latency_ms(std::size_t from, std::size_t to, int repetitions);
  // Devices with memories of their own: the bytes copied between them by
  // the substeps enqueued since the last call, the copies of the last
  // recorded substep, and the plan they follow (nullptr for one memory).
  std::size_t take_bytes_moved();
  std::vector<sched::CopyTiming> copies();
  const plan::TransferPlan* transfer_plan() const;
  // Median time one empty launch occupies a queue (the launch gap).
  double launch_gap_ms(std::size_t device, int repetitions);

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace atssim::device
