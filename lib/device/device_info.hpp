#pragma once
// What atssim knows about an OpenCL device, without exposing OpenCL types.
#include <string>
#include <vector>

namespace atssim::device {

struct SvmCaps {
  bool coarse_buffer = false;
  bool fine_buffer = false;
  bool fine_system = false;
  bool atomics = false;
  bool any() const { return coarse_buffer || fine_buffer || fine_system; }
};

struct DeviceInfo {
  int index = -1;  // position in list_devices()
  int platform_index = -1;
  int platform_device = -1;  // index within its platform (the D of a "P:D" spec)
  std::string platform;
  std::string name;
  std::string vendor;
  std::string type;       // "gpu", "cpu", "accelerator", "other"
  std::string version;    // CL_DEVICE_VERSION
  std::string c_version;  // highest OpenCL C version the device accepts
  int compute_units = 0;
  long long global_memory = 0;  // bytes
  SvmCaps svm;
  int max_sub_devices = 0;  // 0 = cannot be partitioned equally
  int sub_device = -1;      // index within its parent when split, else -1
  int sub_device_count = 0;
};

// Every device of every platform, in platform order. Empty when there is no
// OpenCL platform (not an error here; callers decide).
std::vector<DeviceInfo> list_devices();

// One line per device, as `atssim devices` prints it.
std::string describe(const DeviceInfo& info);
std::string svm_text(const SvmCaps& caps);

}  // namespace atssim::device
