#pragma once
// The one include of the OpenCL C++ bindings (only lib/device uses OpenCL).
#define CL_HPP_TARGET_OPENCL_VERSION 300
#define CL_HPP_MINIMUM_OPENCL_VERSION 200  // SVM needs 2.0 anyway
#define CL_HPP_ENABLE_EXCEPTIONS
#include <CL/opencl.hpp>

#include <string>

namespace atssim::device {

// "CL_OUT_OF_RESOURCES (-5)" for messages.
std::string cl_error_name(int code);

// Throws atssim::Error (runtime) "what: CL_… (-n)" when code != CL_SUCCESS.
void check_cl(int code, const char* what);

}  // namespace atssim::device
