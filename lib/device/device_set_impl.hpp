#pragma once
// OpenCL side of DeviceSet (internal to lib/device).
#include <vector>

#include "device/device_info.hpp"
#include "device/device_set.hpp"
#include "device/opencl.hpp"

namespace atssim::device {

struct DeviceSet::Impl {
  cl::Context context;
  std::vector<cl::Device> devices;
  std::vector<cl::CommandQueue> queues;  // in order, profiling on
  std::vector<DeviceInfo> infos;
};

}  // namespace atssim::device
