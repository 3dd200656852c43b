#include "graph/simd_batches.hpp"

#include <algorithm>
#include <numeric>
#include <utility>

#include <fmt/format.h>

#include "util/error.hpp"

namespace atssim::graph {

template <std::size_t Arity>
SimdOrder schedule_simd_order(std::span<const std::array<int, Arity>> elements, int particle_count, int width) {
  if (width < 1) throw internal_error(fmt::format("schedule_simd: width {} < 1", width));
  const std::size_t n = elements.size();
  std::vector<int> order(n);  // order[i]: the input element now at position i
  std::iota(order.begin(), order.end(), 0);
  // batch_of[p]: the batch that holds particle p (batches numbered from 1).
  std::vector<int> batch_of(static_cast<std::size_t>(std::max(particle_count, 0)), 0);
  auto fits = [&](int e, int batch) {
    for (int p : elements[static_cast<std::size_t>(e)]) {
      if (p >= 0 && p < particle_count && batch_of[static_cast<std::size_t>(p)] == batch) return false;
    }
    return true;
  };
  SimdOrder out;
  int set_size = 0, batch = 0;
  for (std::size_t i = 0; i < n;) {
    if (set_size % width == 0) ++batch;
    // The first remaining element that shares no particle with the batch.
    std::size_t j = i;
    while (j < n && !fits(order[j], batch)) ++j;
    if (j == n) {  // none fits: the set ends, the next one starts with element i
      out.set_sizes.push_back(set_size);
      set_size = 0;
      continue;
    }
    for (int p : elements[static_cast<std::size_t>(order[j])]) {
      if (p >= 0 && p < particle_count) batch_of[static_cast<std::size_t>(p)] = batch;
    }
    std::swap(order[i], order[j]);
    ++set_size;
    ++i;
  }
  if (set_size > 0) out.set_sizes.push_back(set_size);
  std::size_t k = 0;
  for (int size : out.set_sizes) {
    out.slots.insert(out.slots.end(), order.begin() + static_cast<long>(k),
                     order.begin() + static_cast<long>(k + size));
    out.slots.insert(out.slots.end(), static_cast<std::size_t>((width - size % width) % width), -1);
    k += static_cast<std::size_t>(size);
  }
  return out;
}

template SimdOrder schedule_simd_order<2>(std::span<const std::array<int, 2>>, int, int);
template SimdOrder schedule_simd_order<3>(std::span<const std::array<int, 3>>, int, int);
template SimdOrder schedule_simd_order<4>(std::span<const std::array<int, 4>>, int, int);

}  // namespace atssim::graph
