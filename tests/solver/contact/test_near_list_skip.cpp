// The near lists' skip as a whole (common/self_contact_lists.h
// sc_list_apart) against the entry by entry test it stands for
// (contact/self_contact.cl sc_still_apart: d0 > reach and fl(fl(d0 - m0) -
// m1) > reach), on lists built to sit at the edge of float rounding.
#include <catch2/catch.hpp>

#include <cmath>
#include <random>

#include "solver/layout/sim_layout.hpp"

#define ats_float4 ::atssim::solver::Float4
#include "common/self_contact_lists.h"

namespace {

// sc_still_apart's arithmetic, as the kernels write it.
bool entry_apart(float d0, float m0, float m1, float reach) { return d0 > reach && d0 - m0 - m1 > reach; }

}  // namespace

TEST_CASE("a near list skipped as a whole holds only entries the entry by entry test skips",
          "[solver][contact][self]") {
  std::mt19937 rng(20261205);
  std::uniform_real_distribution<float> unit(0.0f, 1.0f);
  const float r = 0.002f, reach = 1.01f * r;
  int lists = 0, skipped = 0, entries_apart = 0, entries = 0;
  for (int l = 0; l < 200000; ++l) {
    // The list's smallest distance and the sides' largest displacements,
    // drawn so that least - first - second lands within a few ulps of the
    // reach in a quarter of the lists.
    const float first = r * unit(rng), second = r * unit(rng);
    float least = reach + first + second;
    if (l % 4 == 0) {
      least = std::nextafter(least, l % 8 == 0 ? 0.0f : 1.0f);
    } else {
      least += r * (unit(rng) - 0.25f);
    }
    ++lists;
    const bool whole = sc_list_apart(least, first, second, reach);
    skipped += whole;
    // Its entries: no nearer than least, no side farther moved than its bound,
    // the extremes included.
    for (int k = 0; k < 8; ++k) {
      const float d0 = k == 0 ? least : least + r * unit(rng) * unit(rng) * 0.01f;
      const float m0 = k < 2 ? first : first * unit(rng);
      const float m1 = k < 3 ? second : second * unit(rng);
      const bool apart = entry_apart(d0, m0, m1, reach);
      ++entries;
      entries_apart += apart;
      if (whole && !apart) FAIL("list skipped with an entry the entry by entry test keeps: least " << least);
    }
  }
  // Not vacuous: most lists far enough apart are skipped, and some at the edge are not.
  CHECK(skipped > lists / 2);
  CHECK(skipped < lists);
  CHECK(entries_apart < entries);
}
