// NvCloth's TripletScheduler (seed 002) and AdjacencyQuerier.
#include <catch2/catch.hpp>

#include <algorithm>
#include <set>
#include <vector>

#include "graph/adjacency.hpp"
#include "graph/triplet_scheduler.hpp"

using namespace atssim;
using graph::Triplet;

namespace {

// The seed's example: a square cloth of 3 x 3 particles (row-major), every
// quad split along the same diagonal ("without alternating diagonals").
std::vector<Triplet> nine_particles() {
  return {{0, 1, 4}, {0, 4, 3}, {1, 2, 5}, {1, 5, 4}, {3, 4, 7}, {3, 7, 6}, {4, 5, 8}, {4, 8, 7}};
}

// An n x n grid of particles, two triangles per quad.
std::vector<Triplet> grid(int n) {
  std::vector<Triplet> t;
  for (int k = 0; k + 1 < n; ++k) {
    for (int i = 0; i + 1 < n; ++i) {
      const int a = k * n + i, b = a + 1, c = a + n, d = c + 1;
      t.push_back({a, c, b});
      t.push_back({b, c, d});
    }
  }
  return t;
}

bool disjoint(const Triplet& a, const Triplet& b) {
  for (int p : a) {
    if (p == b[0] || p == b[1] || p == b[2]) return false;
  }
  return true;
}

std::multiset<Triplet> as_multiset(const std::vector<Triplet>& t) { return {t.begin(), t.end()}; }

}  // namespace

TEST_CASE("the adjacency of the seed's 9-particle cloth: counts, prefix sums and lists by hand", "[graph][nvcloth]") {
  const auto t = nine_particles();
  std::vector<int> flat;
  for (const Triplet& x : t) flat.insert(flat.end(), x.begin(), x.end());
  const graph::Adjacency a = graph::build_adjacency(flat, 3, 9);
  // Triangles per particle: 2 3 1 3 6 3 1 3 2; exclusive prefix sum with the extra last element.
  CHECK(a.offsets == std::vector<int>{0, 2, 5, 6, 9, 15, 18, 19, 22, 24});
  // Lists ascending (NvCloth fills by decrementing, so its lists run descending; the sets are the same).
  CHECK(a.elements == std::vector<int>{0, 1, 0, 2, 3, 2, 1, 4, 5, 0, 1, 3, 4, 6, 7, 2, 3, 6, 5, 4, 5, 7, 6, 7});
}

TEST_CASE("simd batches: a hand-worked reorder and NvCloth's padding with the dummy (n, n+1, n+2)",
          "[graph][nvcloth]") {
  // The second triplet shares particle 2 with the first, so the third moves up.
  const std::vector<Triplet> a{{0, 1, 2}, {2, 3, 4}, {5, 6, 7}, {0, 5, 8}};
  const graph::SimdBatches s = graph::schedule_simd(a, 9, 2);
  CHECK(s.triplets == std::vector<Triplet>{{0, 1, 2}, {5, 6, 7}, {2, 3, 4}, {0, 5, 8}});
  CHECK(s.set_sizes == std::vector<int>{4});
  CHECK(s.padded == s.triplets);
  // A fan around particle 0: no two fit one batch, every set holds one and is padded.
  const std::vector<Triplet> fan{{0, 1, 2}, {0, 3, 4}, {0, 5, 6}};
  const graph::SimdBatches f = graph::schedule_simd(fan, 7, 2);
  CHECK(f.set_sizes == std::vector<int>{1, 1, 1});
  const Triplet d{7, 8, 9};
  CHECK(f.padded == std::vector<Triplet>{{0, 1, 2}, d, {0, 3, 4}, d, {0, 5, 6}, d});
}

TEST_CASE("simd batches are conflict-free, hold every triplet once, and sets are padded to the width",
          "[graph][nvcloth]") {
  const int width = GENERATE(2, 4, 8);
  const int n = GENERATE(5, 12);
  const auto t = grid(n);
  const graph::SimdBatches s = graph::schedule_simd(t, n * n, width);
  CHECK(as_multiset(s.triplets) == as_multiset(t));
  const Triplet dummy{n * n, n * n + 1, n * n + 2};
  std::size_t at = 0, first = 0;
  for (std::size_t k = 0; k < s.set_sizes.size(); ++k) {
    const int size = s.set_sizes[k];
    const int padded = (size + width - 1) / width * width;
    for (int b = 0; b < padded; b += width) {
      for (int i = b; i < b + width; ++i) {
        const Triplet& x = s.padded[at + i];
        if (i >= size) {
          CHECK(x == dummy);  // padding only at the end of a set
          continue;
        }
        CHECK(x == s.triplets[first + i]);
        for (int j = b; j < i; ++j) CHECK(disjoint(x, s.padded[at + j]));
      }
    }
    // A set ends only when no later triplet fits its last batch.
    if (k + 1 < s.set_sizes.size()) {
      const int last = size / width * width == size ? size - width : size / width * width;
      for (std::size_t r = first + size; r < s.triplets.size(); ++r) {
        bool fits = true;
        for (int j = last; j < size; ++j) fits = fits && disjoint(s.triplets[r], s.triplets[first + j]);
        CHECK_FALSE(fits);
      }
    }
    at += static_cast<std::size_t>(padded);
    first += static_cast<std::size_t>(size);
  }
  CHECK(at == s.padded.size());
}

TEST_CASE("warp sets share no particle, hold every triplet once, and count bank replays as brute force does",
          "[graph][nvcloth]") {
  const int width = GENERATE(16, 32);
  const int n = GENERATE(3, 9, 20);
  const auto t = grid(n);
  const graph::WarpSets w = graph::schedule_warp(t, n * n, width);
  CHECK(as_multiset(w.triplets) == as_multiset(t));
  std::size_t first = 0;
  for (int size : w.set_sizes) {
    for (int i = 0; i < size; ++i) {
      for (int j = 0; j < i; ++j) CHECK(disjoint(w.triplets[first + i], w.triplets[first + j]));
    }
    first += static_cast<std::size_t>(size);
  }
  CHECK(first == t.size());
  CHECK(w.set_sizes.size() >= 6);  // an interior grid particle has 6 triangles
  CHECK(w.replays == graph::bank_replays(w.triplets, w.set_sizes, width));
}

TEST_CASE("bank replays by hand: two reads of one bank in a warp cost two executions", "[graph][nvcloth]") {
  // Width 4: slot 0 reads particles 0, 4, 8 (all bank 0); slots 1 and 2 read banks 1, 2, 3.
  const std::vector<Triplet> t{{0, 1, 5}, {4, 2, 6}, {8, 3, 7}};
  CHECK(graph::bank_replays(t, std::vector<int>{3}, 4) == 3 + 1 + 1);
  // Two sets: {t0} costs one execution per slot; {t1, t2} two in slot 0.
  CHECK(graph::bank_replays(t, std::vector<int>{1, 2}, 4) == 3 + (2 + 1 + 1));
}
