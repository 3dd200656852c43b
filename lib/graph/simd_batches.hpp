#pragma once
// NvCloth's TripletScheduler::simd (seed 002) for elements of any arity: the
// XPBD solve's distance constraints (pairs) and bending stencils (quads) as
// well as triangles. Greedy, in input order: each slot of a batch takes the
// first remaining element that shares no particle with the batch so far; when
// none fits, the set ends and is padded to a multiple of `width` with the
// dummy (the particles n, n + 1, … past the last one, NvCloth's paddingDummy).
// Sweeping the padded order batch after batch is a Gauss–Seidel order, and
// the `width` lanes of a batch can run at once.
#include <array>
#include <cstddef>
#include <span>
#include <vector>

namespace atssim::graph {

struct SimdOrder {
  // Per slot of the padded order (sets one after another, each a multiple of
  // width), the index of the input element there, or -1 for the dummy.
  std::vector<int> slots;
  std::vector<int> set_sizes;  // elements per set, before padding
};

template <std::size_t Arity>
SimdOrder schedule_simd_order(std::span<const std::array<int, Arity>> elements, int particle_count, int width);

// The dummy element: particles particle_count, particle_count + 1, ….
template <std::size_t Arity>
std::array<int, Arity> padding_dummy(int particle_count) {
  std::array<int, Arity> d{};
  for (std::size_t k = 0; k < Arity; ++k) d[k] = particle_count + static_cast<int>(k);
  return d;
}

}  // namespace atssim::graph
