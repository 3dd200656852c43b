#pragma once
// What a solver hands the device layer: the buffers it needs, the task graph
// of one substep, and for every task the kernel launches that perform it.
// The device layer runs this without knowing any physics (DESIGN.md).
#include <cstddef>
#include <cstdint>
#include <cstring>
#include <string>
#include <vector>

#include "sched/task_graph.hpp"

namespace atssim::solver {

using BufferId = int;

struct BufferSpec {
  std::string name;                // "x", "v", "stretch", … (for messages and output)
  std::vector<std::byte> initial;  // initial contents; its size is the buffer's size
};

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

struct KernelLaunch {
  std::string kernel;              // kernel name in the plan's program
  std::size_t global_size = 0;     // work-items; 0 = nothing to do
  std::vector<KernelArg> args;
  // When ≥ 0, args[range_arg] and args[range_arg + 1] are the (first, count)
  // of independent elements the launch covers (count == global_size), so it
  // may be cut into sub-ranges that run on different devices.
  int range_arg = -1;
};

struct SubstepPlan {
  std::string program;             // embedded program name, e.g. "xpbd"
  std::vector<BufferSpec> buffers;
  sched::TaskGraph graph;
  std::vector<std::vector<KernelLaunch>> launches;  // indexed by task id
  BufferId positions = -1;         // float4 per particle (xyz used): what output reads
  int particle_count = 0;

  // Appends a buffer; returns its id.
  BufferId add_buffer(std::string name, std::vector<std::byte> initial) {
    buffers.push_back({std::move(name), std::move(initial)});
    return static_cast<BufferId>(buffers.size() - 1);
  }

  // Appends a task with its launches; returns its id.
  sched::TaskId add_task(sched::Task task, std::vector<KernelLaunch> task_launches) {
    const sched::TaskId id = graph.add_task(std::move(task));
    launches.push_back(std::move(task_launches));
    return id;
  }
};

// The bytes of a vector of plain values, as a buffer's initial contents.
template <typename T>
std::vector<std::byte> bytes_of(const std::vector<T>& values) {
  std::vector<std::byte> out(values.size() * sizeof(T));
  if (!out.empty()) std::memcpy(out.data(), values.data(), out.size());
  return out;
}

}  // namespace atssim::solver
