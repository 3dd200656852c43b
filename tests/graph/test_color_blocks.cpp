#include <catch2/catch.hpp>

#include <random>
#include <set>

#include "graph/color_blocks.hpp"
#include "model/cloth_builder.hpp"

using namespace atssim;

namespace {

void check_blocks(const std::vector<int>& elements, int arity, const std::vector<char>& movable) {
  const auto blocks = graph::color_elements(elements, arity, movable);
  const int count = static_cast<int>(elements.size()) / arity;
  std::vector<int> seen(count, 0);
  for (int b = 0; b < blocks.count(); ++b) {
    CHECK_FALSE(blocks.block(b).empty());
    std::set<int> used;
    for (int e : blocks.block(b)) {
      ++seen[e];
      for (int k = 0; k < arity; ++k) {
        const int v = elements[e * arity + k];
        if (!movable[v]) continue;
        CHECK(used.insert(v).second);  // no movable particle twice in a block
      }
    }
  }
  for (int e = 0; e < count; ++e) CHECK(seen[e] == 1);  // every element in exactly one block
}

}  // namespace

TEST_CASE("color blocks share no particle and hold every element once (grid edges)") {
  const auto mesh = model::make_grid_mesh({{1.0, 1.0}, {20, 17}});
  std::vector<int> flat;
  for (const auto& e : model::unique_edges(mesh.triangles)) flat.insert(flat.end(), e.begin(), e.end());
  check_blocks(flat, 2, std::vector<char>(mesh.vertices.size(), 1));
  const auto blocks = graph::color_elements(flat, 2, std::vector<char>(mesh.vertices.size(), 1));
  CHECK(blocks.count() <= 8);  // max degree 6 on this grid; greedy stays close
}

TEST_CASE("color blocks share no particle for random 4-vertex stencils") {
  std::mt19937 rng(7);
  std::uniform_int_distribution<int> pick(0, 79);
  std::vector<int> flat;
  for (int e = 0; e < 400; ++e) {
    std::set<int> stencil;  // four distinct particles, like a bending stencil
    while (stencil.size() < 4) stencil.insert(pick(rng));
    flat.insert(flat.end(), stencil.begin(), stencil.end());
  }
  check_blocks(flat, 4, std::vector<char>(80, 1));
}

TEST_CASE("pinned particles create no conflict") {
  // A star: every edge touches particle 0. Movable: one block per edge; pinned: one block.
  std::vector<int> flat;
  for (int i = 1; i <= 6; ++i) flat.insert(flat.end(), {0, i});
  std::vector<char> movable(7, 1);
  CHECK(graph::color_elements(flat, 2, movable).count() == 6);
  movable[0] = 0;
  CHECK(graph::color_elements(flat, 2, movable).count() == 1);
  check_blocks(flat, 2, movable);
}

TEST_CASE("elements inside a block are sorted by their smallest particle") {
  const auto mesh = model::make_grid_mesh({{1.0, 1.0}, {10, 10}});
  std::vector<int> flat;
  for (const auto& e : model::unique_edges(mesh.triangles)) flat.insert(flat.end(), e.begin(), e.end());
  const auto blocks = graph::color_elements(flat, 2, std::vector<char>(100, 1));
  for (int b = 0; b < blocks.count(); ++b) {
    int last = -1;
    for (int e : blocks.block(b)) {
      const int m = std::min(flat[2 * e], flat[2 * e + 1]);
      CHECK(m >= last);
      last = m;
    }
  }
}
