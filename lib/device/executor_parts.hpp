#pragma once
// What the two ways of running a plan share (internal to lib/device): the
// order of the tasks with their devices and waits, and the plan's buffers
// and programs in each memory.
#include <cstddef>
#include <vector>

#include "device/device_set_impl.hpp"
#include "device/opencl.hpp"
#include "plan/element_sets.hpp"
#include "plan/substep_plan.hpp"
#include "plan/transfer_plan.hpp"
#include "sched/ids.hpp"

namespace atssim::device {

// One task in the order an executor starts them (plan::ExecutionStep): on
// which device, and the tasks of other devices it must wait for.
using Step = plan::ExecutionStep;

struct PlanResources {
  const DeviceSet::Impl& set;
  const plan::SubstepPlan& plan;
  std::vector<std::vector<void*>> buffers;  // per memory (context), per buffer: its SVM pointer there
  std::vector<std::size_t> sizes;           // bytes per buffer
  std::vector<cl::Program> programs;        // per memory
  std::vector<std::vector<int>> functions;  // per task, per launch: its dispatcher case (launch_binding.hpp)
  std::vector<plan::ElementSets> written;   // per task: the bytes it writes (copies between memories)

  void* buffer(std::size_t device, plan::BufferId b) const { return buffers[set.memory_of[device]][b]; }
  const cl::Program& program(std::size_t device) const { return programs[set.memory_of[device]]; }
};

// "-cl-std=CL3.0" where every device accepts OpenCL C 3.0, else CL2.0 where
// every device accepts 2.0 (the fused dispatcher needs its atomics), else
// CL1.2 (events only: the task kernels are OpenCL C 1.2).
std::string language_option(const DeviceSet::Impl& set);

}  // namespace atssim::device
