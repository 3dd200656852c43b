#pragma once
// What a plan carries from one substep to the next: the contents of its
// positions and velocities buffers, and of its carried buffers (BufferRole).
// Every other buffer is rewritten within a substep before it is read, except
// caches, which a cache_state buffer marks invalid on reset: they are remade
// from the carried buffers, as they were. This is all an executor needs to
// restart a run, repeat a substep or resume at a frame, bit for bit.
#include <cstddef>
#include <vector>

namespace atssim::plan {

struct PlanState {
  std::vector<std::byte> positions;
  std::vector<std::byte> velocities;  // empty when the plan has none
  // The carried buffers' bytes, one after another in the plan's order;
  // empty: their initial contents (a state from positions and velocities
  // alone, such as a new plan's start or another plan's state).
  std::vector<std::byte> carried;
};

}  // namespace atssim::plan
