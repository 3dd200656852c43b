#pragma once
// Which elements of a buffer a launch writes, as a function of its range
// (DESIGN.md "Devices": devices that share no memory copy what another
// device wrote before they read it, and the copies are priced by size).
// Declared by the solver that builds the launch, so that the plan layer and
// the executors need no physics to know what to copy — exactly, since two
// devices may write interleaved elements of one buffer in the same block:
//   elements: element e of the launch writes buffer element (offset + e)
//             (a per-particle task, a per-constraint multiplier);
//   indexed:  element e writes buffer elements table[arity e … arity e +
//             arity − 1] (a constraint's particles, a color's vertices);
//   whole:    the whole buffer (what an executor assumes for a writable
//             argument that a launch does not describe).
// Buffer elements are `element_bytes` each (16 for a float4 particle).
#include <cstddef>
#include <cstdint>
#include <memory>
#include <vector>

#include "plan/buffer.hpp"

namespace atssim::plan {

struct WriteSpan {
  enum class Kind { whole, elements, indexed };
  BufferId buffer = -1;
  Kind kind = Kind::whole;
  std::uint32_t element_bytes = 4;
  std::int32_t offset = 0;                                 // elements
  std::int32_t arity = 0;                                  // indexed
  std::shared_ptr<const std::vector<std::int32_t>> table;  // indexed: arity entries per element of the index space

  static WriteSpan whole_buffer(BufferId b) { return {b, Kind::whole, 4, 0, 0, nullptr}; }
  static WriteSpan per_element(BufferId b, std::uint32_t bytes, std::int32_t offset = 0) {
    return {b, Kind::elements, bytes, offset, 0, nullptr};
  }
  static WriteSpan per_index(BufferId b, std::uint32_t bytes, std::int32_t arity,
                             std::shared_ptr<const std::vector<std::int32_t>> table) {
    return {b, Kind::indexed, bytes, 0, arity, std::move(table)};
  }
};

}  // namespace atssim::plan
