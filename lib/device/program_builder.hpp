#pragma once
// Builds an embedded OpenCL program for a context (internal to lib/device).
#include <string>
#include <vector>

#include "device/opencl.hpp"

namespace atssim::device {

// Throws atssim::Error (runtime) with the compiler's build log on failure.
cl::Program build_program(const cl::Context& context, const std::vector<cl::Device>& devices,
                          const std::string& program_name);

}  // namespace atssim::device
