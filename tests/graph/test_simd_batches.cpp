// NvCloth's simd batches for any arity (graph/simd_batches): the order that
// XPBD's solver.ordering: batches sweeps.
#include <catch2/catch.hpp>

#include <array>
#include <set>
#include <vector>

#include "graph/simd_batches.hpp"

using namespace atssim;

namespace {

using Pair = std::array<int, 2>;
using Quad = std::array<int, 4>;

// The springs of an n x n particle grid: rows, columns, both diagonals.
std::vector<Pair> grid_springs(int n) {
  std::vector<Pair> s;
  for (int k = 0; k < n; ++k) {
    for (int i = 0; i < n; ++i) {
      const int a = k * n + i;
      if (i + 1 < n) s.push_back({a, a + 1});
      if (k + 1 < n) s.push_back({a, a + n});
      if (i + 1 < n && k + 1 < n) s.push_back({a, a + n + 1});
      if (i > 0 && k + 1 < n) s.push_back({a, a + n - 1});
    }
  }
  return s;
}

// Bending stencils of the grid: each interior edge of the rows with its wings.
std::vector<Quad> grid_stencils(int n) {
  std::vector<Quad> q;
  for (int k = 1; k + 1 < n; ++k) {
    for (int i = 0; i + 1 < n; ++i) {
      const int a = k * n + i;
      q.push_back({a, a + 1, a - n, a + n + 1});
    }
  }
  return q;
}

// Every element exactly once, every batch of `width` slots free of shared
// particles (the dummy aside), sets padded to whole batches.
template <std::size_t N>
void check_order(const std::vector<std::array<int, N>>& e, const graph::SimdOrder& o, int width) {
  REQUIRE(o.slots.size() % static_cast<std::size_t>(width) == 0);
  std::multiset<int> seen;
  for (int s : o.slots) {
    if (s >= 0) seen.insert(s);
  }
  REQUIRE(seen.size() == e.size());
  for (int i = 0; i < static_cast<int>(e.size()); ++i) CHECK(seen.count(i) == 1);
  int conflicts = 0;
  for (std::size_t b = 0; b < o.slots.size(); b += static_cast<std::size_t>(width)) {
    std::set<int> particles;
    std::size_t used = 0;
    for (std::size_t l = 0; l < static_cast<std::size_t>(width); ++l) {
      const int s = o.slots[b + l];
      if (s < 0) continue;
      for (int p : e[static_cast<std::size_t>(s)]) particles.insert(p);
      used += N;
    }
    conflicts += particles.size() == used ? 0 : 1;
  }
  CHECK(conflicts == 0);
  std::size_t padded = 0;
  for (int size : o.set_sizes) padded += static_cast<std::size_t>((size + width - 1) / width * width);
  CHECK(padded == o.slots.size());
}

}  // namespace

TEST_CASE("simd order of pairs: a hand-worked reorder, the set end and NvCloth's dummy", "[graph][nvcloth]") {
  // Width 2. {0,1} opens batch 1; {1,2} shares 1, so {3,4} joins it. Batch 2:
  // {1,2}, then {2,3} shares 2 and nothing else is left: the set ends at 3
  // elements, padded with one dummy; {2,3} starts the next set.
  const std::vector<Pair> e{{0, 1}, {1, 2}, {3, 4}, {2, 3}};
  const graph::SimdOrder o = graph::schedule_simd_order<2>(e, 5, 2);
  CHECK(o.slots == std::vector<int>{0, 2, 1, -1, 3, -1});
  CHECK(o.set_sizes == std::vector<int>{3, 1});
  CHECK(graph::padding_dummy<2>(5) == Pair{5, 6});
}

TEST_CASE("simd order of a grid cloth's springs and bending stencils: each element once, every batch conflict-free",
          "[graph][nvcloth]") {
  const int width = GENERATE(1, 4, 8);
  const auto springs = grid_springs(12);
  check_order(springs, graph::schedule_simd_order<2>(springs, 144, width), width);
  const auto stencils = grid_stencils(12);
  check_order(stencils, graph::schedule_simd_order<4>(stencils, 144, width), width);
}

TEST_CASE("simd order: a width below 1 is refused", "[graph][nvcloth]") {
  const std::vector<Pair> e{{0, 1}};
  CHECK_THROWS(graph::schedule_simd_order<2>(e, 2, 0));
}
