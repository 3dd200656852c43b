#pragma once
// Runs a solver's SubstepPlan on the devices of a DeviceSet: every buffer in
// SVM, one OpenCL kernel object per launch with its arguments set once,
// tasks enqueued in order on an in-order queue. Knows nothing of physics.
#include <memory>
#include <vector>

#include "device/device_set.hpp"
#include "solver/substep_plan.hpp"

namespace atssim::device {

enum class SvmMode { automatic, coarse, fine };

struct ExecutorOptions {
  SvmMode svm = SvmMode::automatic;  // automatic: fine grain when every device offers it
  std::size_t device = 0;            // which device of the set runs the plan
  std::size_t local_size = 64;       // fixed per kernel: pocl recompiles for each new size
};

class PlanExecutor {
 public:
  // Builds the plan's program (errors carry the build log) and uploads the
  // buffers' initial contents.
  PlanExecutor(const DeviceSet& devices, const solver::SubstepPlan& plan, ExecutorOptions options = {});
  PlanExecutor(const PlanExecutor&) = delete;
  PlanExecutor& operator=(const PlanExecutor&) = delete;
  ~PlanExecutor();

  // Enqueues `count` substeps; returns without waiting.
  void enqueue_substeps(int count);
  // Waits for everything enqueued.
  void finish();
  // Copies a buffer to the host (waits first).
  std::vector<std::byte> read(solver::BufferId id);
  // Positions as xyz float triplets (from the plan's float4 position buffer).
  void read_positions(std::vector<float>& xyz);
  bool fine_grain() const;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace atssim::device
