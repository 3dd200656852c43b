#pragma once
// OpenCL programs embedded into the binary at build time (kernels/*.cl with
// their common/ headers inlined).
#include <string_view>

namespace atssim::kernels {

// The full source of the named program ("xpbd"), or nullptr if unknown.
const char* program_source(std::string_view name);

}  // namespace atssim::kernels
