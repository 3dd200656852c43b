#pragma once
// One launch of a task function over a range of independent elements. The
// function is named as it is declared in the plan's OpenCL program
// (`ATS_TASK void name(int i, …)`, kernels/README in docs/architecture.md);
// its parameters after the element index are `args`, checked against that
// declaration when an executor is built. The range is not an argument: the
// executor hands each work-item (events) or work-group (fused) its share.
#include <cstdint>
#include <string>
#include <vector>

#include "plan/buffer.hpp"
#include "plan/write_span.hpp"

namespace atssim::plan {

struct KernelArg {
  enum class Kind { buffer, i32, f32 };
  Kind kind = Kind::i32;
  BufferId buffer = -1;
  std::int32_t i32 = 0;
  float f32 = 0.0f;

  static KernelArg of_buffer(BufferId id) { return {Kind::buffer, id, 0, 0.0f}; }
  static KernelArg of_int(std::int32_t v) { return {Kind::i32, -1, v, 0.0f}; }
  static KernelArg of_float(float v) { return {Kind::f32, -1, 0, v}; }
};

// Elements [first, first + count) of the task function's index space.
struct Range {
  std::int32_t first = 0;
  std::int32_t count = 0;
};

struct KernelLaunch {
  std::string function;         // task function of the plan's program
  Range range;                  // count 0 = nothing to do
  std::vector<KernelArg> args;  // the function's parameters after the element index
  // What it writes (write_span.hpp); a writable buffer argument it does not
  // list is taken to be written whole.
  std::vector<WriteSpan> writes;
};

}  // namespace atssim::plan
