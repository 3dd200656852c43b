#pragma once
// What a plan carries from one substep to the next: the contents of its
// positions and velocities buffers. Every other buffer is rewritten within a
// substep before it is read (BufferRole), except caches, which a frame_state
// buffer marks invalid when a frame starts and on reset (so a restarted run
// rebuilds them): this is all an executor needs to restart a run, repeat a
// substep or resume at a frame.
#include <cstddef>
#include <vector>

namespace atssim::plan {

struct PlanState {
  std::vector<std::byte> positions;
  std::vector<std::byte> velocities;  // empty when the plan has none
};

}  // namespace atssim::plan
