#include "device/program_builder.hpp"

#include <deque>
#include <mutex>
#include <tuple>

#include <fmt/format.h>

#include "kernels/embedded_programs.hpp"
#include "util/error.hpp"

namespace atssim::device {

namespace {

// The programs built last, by context, devices, name and options: an
// executor built again for the same devices (converge and run --tolerance
// build one per iteration count) takes the built program instead of
// building it again (~0.1 s with pocl, most of an executor's start). A
// cached program keeps its context alive, so the few kept are the newest.
struct CachedProgram {
  cl_context context;
  std::vector<cl_device_id> devices;
  std::string name, options;
  cl::Program program;
};
constexpr std::size_t kCachedPrograms = 8;
std::mutex cache_mutex;
std::deque<CachedProgram> cache;

std::vector<cl_device_id> ids_of(const std::vector<cl::Device>& devices) {
  std::vector<cl_device_id> ids;
  for (const cl::Device& d : devices) ids.push_back(d());
  return ids;
}

}  // namespace

cl::Program build_program(const cl::Context& context, const std::vector<cl::Device>& devices,
                          const std::string& program_name, const std::string& options) {
  const std::vector<cl_device_id> ids = ids_of(devices);
  {
    const std::lock_guard<std::mutex> lock(cache_mutex);
    for (const CachedProgram& c : cache) {
      if (c.context == context() && c.devices == ids && c.name == program_name && c.options == options) {
        return c.program;
      }
    }
  }
  cl::Program program = build_uncached(context, devices, program_name, options);
  const std::lock_guard<std::mutex> lock(cache_mutex);
  cache.push_front({context(), ids, program_name, options, program});
  if (cache.size() > kCachedPrograms) cache.pop_back();
  return program;
}

cl::Program build_uncached(const cl::Context& context, const std::vector<cl::Device>& devices,
                           const std::string& program_name, const std::string& options) {
  const char* source = kernels::program_source(program_name);
  if (source == nullptr) throw Error(fmt::format("no embedded OpenCL program named '{}'", program_name));
  cl::Program program(context, std::string(source));
  try {
    program.build(devices, options.c_str());
  } catch (const cl::BuildError& e) {
    std::string log;
    for (const auto& [device, text] : e.getBuildLog()) log += text;
    throw runtime_error(fmt::format("OpenCL program '{}' failed to compile:\n{}", program_name, log));
  } catch (const cl::Error& e) {
    std::string log;
    for (const cl::Device& d : devices) log += program.getBuildInfo<CL_PROGRAM_BUILD_LOG>(d);
    throw runtime_error(
        fmt::format("OpenCL program '{}' failed to build ({}):\n{}", program_name, cl_error_name(e.err()), log));
  }
  return program;
}

}  // namespace atssim::device
