#pragma once
// OpenCL side of DeviceSet (internal to lib/device).
#include <vector>

#include "device/device_info.hpp"
#include "device/device_set.hpp"
#include "device/opencl.hpp"

namespace atssim::device {

struct DeviceSet::Impl {
  // One context per memory: the devices of one platform share one (and its
  // SVM), unless the set was opened with separate memories; then every
  // device has a context, and data moves between them through the host.
  std::vector<cl::Context> contexts;
  std::vector<std::size_t> memory_of;  // per device: its context
  std::vector<cl::Device> devices;
  std::vector<cl::CommandQueue> queues;  // in order, profiling on
  std::vector<DeviceInfo> infos;

  bool one_memory() const { return contexts.size() == 1; }
  const cl::Context& context_of(std::size_t device) const { return contexts.at(memory_of.at(device)); }
  // The devices whose memory is context `memory`.
  std::vector<cl::Device> devices_of(std::size_t memory) const {
    std::vector<cl::Device> out;
    for (std::size_t d = 0; d < devices.size(); ++d) {
      if (memory_of[d] == memory) out.push_back(devices[d]);
    }
    return out;
  }
};

}  // namespace atssim::device
