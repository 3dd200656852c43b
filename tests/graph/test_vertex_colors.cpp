#include <catch2/catch.hpp>

#include <random>
#include <set>

#include "graph/vertex_colors.hpp"
#include "model/cloth_builder.hpp"

using namespace atssim;

TEST_CASE("vertex colors: no two particles of a color share an element, and each movable particle has one") {
  const auto mesh = model::make_grid_mesh({{1.0, 1.0}, {12, 9}});
  std::vector<int> edges, stencils;
  for (const auto& e : model::unique_edges(mesh.triangles)) edges.insert(edges.end(), e.begin(), e.end());
  for (const auto& s : model::bending_stencils(mesh.triangles)) stencils.insert(stencils.end(), s.begin(), s.end());
  const int n = static_cast<int>(mesh.vertices.size());
  std::vector<char> movable(n, 1);
  movable[0] = movable[11] = 0;  // two pinned corners
  const graph::ElementSet sets[] = {{edges, 2}, {stencils, 4}};
  const auto blocks = graph::color_vertices(sets, movable);

  std::vector<int> color(n, -1), seen(n, 0);
  for (int b = 0; b < blocks.count(); ++b) {
    for (int v : blocks.block(b)) {
      color[v] = b;
      ++seen[v];
    }
  }
  for (int v = 0; v < n; ++v) CHECK(seen[v] == (movable[v] ? 1 : 0));
  for (const auto& set : sets) {
    for (std::size_t e = 0; e * set.arity < set.vertices.size(); ++e) {
      for (int a = 0; a < set.arity; ++a) {
        for (int b = a + 1; b < set.arity; ++b) {
          const int u = set.vertices[e * set.arity + a], w = set.vertices[e * set.arity + b];
          if (color[u] >= 0 && color[w] >= 0) CHECK(color[u] != color[w]);
        }
      }
    }
  }
  // The 4 particles of a bending stencil conflict pairwise: at least 4
  // colors; a particle has 12 distinct stencil neighbours on this grid, so
  // greedy needs at most 13.
  CHECK(blocks.count() >= 4);
  CHECK(blocks.count() <= 13);
}
