#pragma once
// Device discovery on the OpenCL side (internal to lib/device).
#include <vector>

#include "device/device_info.hpp"
#include "device/opencl.hpp"

namespace atssim::device {

struct DeviceHandle {
  cl::Device device;
  DeviceInfo info;
};

// All devices of all platforms; an empty list when no platform exists.
std::vector<DeviceHandle> all_device_handles();

DeviceInfo query_info(const cl::Device& device, int index, int platform_index, const std::string& platform_name);

}  // namespace atssim::device
