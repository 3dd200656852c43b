#pragma once
// Sets of buffer elements (what a task writes, what a copy between memories
// carries), and what a launch writes (write_span.hpp).
#include <span>
#include <vector>

#include "plan/kernel_launch.hpp"

namespace atssim::plan {

// Elements of one buffer, sorted and unique, `element_bytes` each.
struct ElementSet {
  BufferId buffer = -1;
  std::uint32_t element_bytes = 4;
  std::vector<std::int32_t> indices;

  std::size_t bytes() const { return indices.size() * element_bytes; }
  // Whether the indices are one run first, first + 1, … (a plain range copy).
  bool contiguous() const;
};

// Element sets of several buffers, one per buffer. Adding a set of another
// element size for a buffer turns both into 4-byte words, so a union is
// always exact.
class ElementSets {
 public:
  void add(const ElementSet& set);
  void add(const ElementSets& other);
  const std::vector<ElementSet>& sets() const { return sets_; }
  std::size_t bytes() const;
  bool empty() const { return sets_.empty(); }

  friend bool operator==(const ElementSets&, const ElementSets&) = default;

 private:
  std::vector<ElementSet> sets_;  // by buffer
};

bool operator==(const ElementSet& a, const ElementSet& b);

// What `launch` writes over its range: its declared spans, plus the whole of
// every writable buffer argument (writable[a]: argument a is a pointer the
// function may write through) that no span names. `buffer_bytes` gives each
// buffer's size; indices past it are dropped.
ElementSets written_elements(const KernelLaunch& launch, std::span<const char> writable,
                             std::span<const std::size_t> buffer_bytes);

}  // namespace atssim::plan
