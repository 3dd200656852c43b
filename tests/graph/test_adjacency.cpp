#include <catch2/catch.hpp>

#include <algorithm>
#include <random>

#include "graph/adjacency.hpp"

using namespace atssim;

TEST_CASE("the CSR adjacency equals a brute-force count") {
  const int arity = GENERATE(2, 3, 4);
  std::mt19937 rng(1234 + arity);
  const int particles = 50;
  std::uniform_int_distribution<int> pick(0, particles - 1);
  std::vector<int> elements;
  for (int e = 0; e < 300; ++e) {
    for (int k = 0; k < arity; ++k) elements.push_back(pick(rng));
  }
  const auto adj = graph::build_adjacency(elements, arity, particles);
  REQUIRE(adj.offsets.size() == particles + 1);
  CHECK(adj.offsets.front() == 0);
  CHECK(adj.offsets.back() == static_cast<int>(elements.size()));
  for (int p = 0; p < particles; ++p) {
    std::vector<int> expected;  // brute force: scan every element slot
    for (int e = 0; e < 300; ++e) {
      for (int k = 0; k < arity; ++k) {
        if (elements[e * arity + k] == p) expected.push_back(e);
      }
    }
    const auto got = adj.of(p);
    CHECK(std::vector<int>(got.begin(), got.end()) == expected);
  }
}
