#pragma once
// Builds an embedded OpenCL program for a context (internal to lib/device).
#include <string>
#include <vector>

#include "device/opencl.hpp"

namespace atssim::device {

// Throws atssim::Error (runtime) with the compiler's build log on failure.
// `options` go to clBuildProgram (e.g. "-cl-std=CL3.0 -DATS_TASK_CLOCK=1").
// Programs built before for the same context, devices, name and options are
// taken from a small cache.
cl::Program build_program(const cl::Context& context, const std::vector<cl::Device>& devices,
                          const std::string& program_name, const std::string& options = "-cl-std=CL1.2");
// The same, always built.
cl::Program build_uncached(const cl::Context& context, const std::vector<cl::Device>& devices,
                           const std::string& program_name, const std::string& options = "-cl-std=CL1.2");

}  // namespace atssim::device
