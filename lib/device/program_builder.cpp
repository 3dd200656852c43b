#include "device/program_builder.hpp"

#include <fmt/format.h>

#include "kernels/embedded_programs.hpp"
#include "util/error.hpp"

namespace atssim::device {

cl::Program build_program(const cl::Context& context, const std::vector<cl::Device>& devices,
                          const std::string& program_name, const std::string& options) {
  const char* source = kernels::program_source(program_name);
  if (source == nullptr) throw internal_error(fmt::format("no embedded OpenCL program named '{}'", program_name));
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
