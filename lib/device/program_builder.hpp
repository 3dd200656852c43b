#pragma once
// Builds an embedded OpenCL program for a context (internal to lib/device).
#include <string>
#include <vector>

#include "device/opencl.hpp"

namespace atssim::device {

// Built once per program, options, context and devices in a process (later
// calls return the same program). Throws atssim::Error (runtime) with the
// compiler's build log on failure.
// `options` go to clBuildProgram (e.g. "-cl-std=CL3.0 -DATS_TASK_CLOCK=1").
cl::Program build_program(const cl::Context& context, const std::vector<cl::Device>& devices,
                          const std::string& program_name, const std::string& options = "-cl-std=CL1.2");

}  // namespace atssim::device
