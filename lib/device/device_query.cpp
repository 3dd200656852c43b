#include "device/device_query.hpp"

#include <algorithm>

namespace atssim::device {

namespace {

std::string type_name(cl_device_type t) {
  if (t & CL_DEVICE_TYPE_GPU) return "gpu";
  if (t & CL_DEVICE_TYPE_CPU) return "cpu";
  if (t & CL_DEVICE_TYPE_ACCELERATOR) return "accelerator";
  return "other";
}

// Highest OpenCL C version the device accepts: CL_DEVICE_OPENCL_C_ALL_VERSIONS
// (3.0) can list more than CL_DEVICE_OPENCL_C_VERSION says (pocl reports 1.2).
std::string c_version(const cl::Device& d) {
  std::string best = d.getInfo<CL_DEVICE_OPENCL_C_VERSION>();
  cl_uint major = 0, minor = 0;
  std::size_t bytes = 0;
  if (clGetDeviceInfo(d(), CL_DEVICE_OPENCL_C_ALL_VERSIONS, 0, nullptr, &bytes) == CL_SUCCESS && bytes > 0) {
    std::vector<cl_name_version> all(bytes / sizeof(cl_name_version));
    clGetDeviceInfo(d(), CL_DEVICE_OPENCL_C_ALL_VERSIONS, bytes, all.data(), nullptr);
    for (const auto& v : all) {
      const cl_uint ma = CL_VERSION_MAJOR(v.version), mi = CL_VERSION_MINOR(v.version);
      if (ma > major || (ma == major && mi > minor)) {
        major = ma;
        minor = mi;
      }
    }
    if (major > 0) best = "OpenCL C " + std::to_string(major) + "." + std::to_string(minor);
  }
  return best;
}

}  // namespace

DeviceInfo query_info(const cl::Device& d, int index, int platform_index, const std::string& platform_name) {
  DeviceInfo info;
  info.index = index;
  info.platform_index = platform_index;
  info.platform = platform_name;
  info.name = d.getInfo<CL_DEVICE_NAME>();
  info.vendor = d.getInfo<CL_DEVICE_VENDOR>();
  info.type = type_name(d.getInfo<CL_DEVICE_TYPE>());
  info.version = d.getInfo<CL_DEVICE_VERSION>();
  info.c_version = c_version(d);
  info.compute_units = static_cast<int>(d.getInfo<CL_DEVICE_MAX_COMPUTE_UNITS>());
  info.global_memory = static_cast<long long>(d.getInfo<CL_DEVICE_GLOBAL_MEM_SIZE>());
  cl_device_svm_capabilities svm = 0;
  if (clGetDeviceInfo(d(), CL_DEVICE_SVM_CAPABILITIES, sizeof(svm), &svm, nullptr) != CL_SUCCESS) svm = 0;
  info.svm.coarse_buffer = (svm & CL_DEVICE_SVM_COARSE_GRAIN_BUFFER) != 0;
  info.svm.fine_buffer = (svm & CL_DEVICE_SVM_FINE_GRAIN_BUFFER) != 0;
  info.svm.fine_system = (svm & CL_DEVICE_SVM_FINE_GRAIN_SYSTEM) != 0;
  info.svm.atomics = (svm & CL_DEVICE_SVM_ATOMICS) != 0;
  cl_uint max_sub = 0;
  std::size_t bytes = 0;
  if (clGetDeviceInfo(d(), CL_DEVICE_PARTITION_PROPERTIES, 0, nullptr, &bytes) == CL_SUCCESS && bytes > 0) {
    std::vector<cl_device_partition_property> props(bytes / sizeof(cl_device_partition_property));
    clGetDeviceInfo(d(), CL_DEVICE_PARTITION_PROPERTIES, bytes, props.data(), nullptr);
    if (std::find(props.begin(), props.end(), CL_DEVICE_PARTITION_EQUALLY) != props.end()) {
      clGetDeviceInfo(d(), CL_DEVICE_PARTITION_MAX_SUB_DEVICES, sizeof(max_sub), &max_sub, nullptr);
    }
  }
  info.max_sub_devices = static_cast<int>(max_sub);
  return info;
}

std::vector<DeviceHandle> all_device_handles() {
  cl_uint count = 0;
  if (clGetPlatformIDs(0, nullptr, &count) != CL_SUCCESS || count == 0) return {};
  std::vector<cl_platform_id> ids(count);
  clGetPlatformIDs(count, ids.data(), nullptr);
  std::vector<DeviceHandle> out;
  for (cl_uint p = 0; p < count; ++p) {
    cl::Platform platform(ids[p], true);
    const std::string pname = platform.getInfo<CL_PLATFORM_NAME>();
    cl_uint n = 0;
    if (clGetDeviceIDs(ids[p], CL_DEVICE_TYPE_ALL, 0, nullptr, &n) != CL_SUCCESS || n == 0) continue;
    std::vector<cl_device_id> devs(n);
    clGetDeviceIDs(ids[p], CL_DEVICE_TYPE_ALL, n, devs.data(), nullptr);
    for (cl_uint k = 0; k < n; ++k) {
      cl::Device d(devs[k], true);
      out.push_back({d, query_info(d, static_cast<int>(out.size()), static_cast<int>(p), pname)});
      out.back().info.platform_device = static_cast<int>(k);
    }
  }
  return out;
}

}  // namespace atssim::device
