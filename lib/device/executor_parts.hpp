#pragma once
// What the two ways of running a plan share (internal to lib/device): the
// order of the tasks with their devices and waits, and the plan's buffers
// and program on the devices.
#include <cstddef>
#include <vector>

#include "device/device_set_impl.hpp"
#include "device/opencl.hpp"
#include "plan/substep_plan.hpp"
#include "sched/ids.hpp"

namespace atssim::device {

// One task in the order an executor starts them: on which device, and the
// tasks of other devices it must wait for (within the substep).
struct Step {
  sched::TaskId task = 0;
  std::size_t device = 0;
  std::vector<sched::TaskId> waits;

  friend bool operator==(const Step&, const Step&) = default;
};

struct PlanResources {
  const DeviceSet::Impl& set;
  const plan::SubstepPlan& plan;
  std::vector<void*> buffers;      // SVM pointer per buffer
  std::vector<std::size_t> sizes;  // bytes per buffer
  cl::Program program;
  std::vector<std::vector<int>> functions;  // per task, per launch: its dispatcher case (launch_binding.hpp)
};

// "-cl-std=CL3.0" where every device accepts OpenCL C 3.0, else CL2.0: the
// dispatcher needs the 2.0 atomics.
std::string language_option(const DeviceSet::Impl& set);

}  // namespace atssim::device
