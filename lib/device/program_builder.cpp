#include "device/program_builder.hpp"

#include <cstdlib>
#include <map>
#include <mutex>
#include <tuple>

#include <fmt/format.h>

#include "kernels/embedded_programs.hpp"
#include "util/error.hpp"

namespace atssim::device {

namespace {

// One build per program, options, context and devices in a process: every
// run of a test process (and every executor of one run) asks for the same
// few programs, and even a build that pocl finds in its cache preprocesses
// the whole source again (~0.1 s each, 3 to 7 builds per run measured).
// Kernels are made per executor from the program; the programs hold no
// program-scope variables, so executors share nothing through them.
using ProgramKey = std::tuple<cl_context, std::vector<cl_device_id>, std::string, std::string>;

cl::Program build(const cl::Context& context, const std::vector<cl::Device>& devices, const std::string& program_name,
                  const std::string& flags) {
  const char* source = kernels::program_source(program_name);
  if (source == nullptr) throw internal_error(fmt::format("no embedded OpenCL program named '{}'", program_name));
  cl::Program program(context, std::string(source));
  try {
    program.build(devices, flags.c_str());
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

}  // namespace

cl::Program build_program(const cl::Context& context, const std::vector<cl::Device>& devices,
                          const std::string& program_name, const std::string& options) {
  // "-w": pocl's compiler prints its warnings on stderr ("2 warnings
  // generated."), a line of the driver's own in the middle of a run's
  // output; ATSSIM_KERNEL_WARNINGS=1 shows them when working on the kernels.
  const char* show = std::getenv("ATSSIM_KERNEL_WARNINGS");
  const std::string flags = show != nullptr && std::string(show) == "1" ? options : options + " -w";
  std::vector<cl_device_id> ids;
  for (const cl::Device& d : devices) ids.push_back(d());
  ProgramKey key{context(), std::move(ids), program_name, flags};
  // Leaked on purpose, like the device sets whose contexts the programs use
  // (DeviceSet::open): kept until exit.
  static auto* built = new std::map<ProgramKey, cl::Program>();
  static std::mutex mutex;
  const std::lock_guard<std::mutex> lock(mutex);
  if (const auto it = built->find(key); it != built->end()) return it->second;
  cl::Program program = build(context, devices, program_name, flags);
  built->emplace(std::move(key), program);
  return program;
}

}  // namespace atssim::device
