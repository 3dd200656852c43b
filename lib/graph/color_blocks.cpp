#include "graph/color_blocks.hpp"

#include <algorithm>
#include <numeric>

#include "graph/adjacency.hpp"
#include "graph/greedy_color.hpp"

namespace atssim::graph {

ColorBlocks color_elements(std::span<const int> element_vertices, int arity, std::span<const char> movable) {
  const int elements = static_cast<int>(element_vertices.size()) / arity;
  // Neighbours through the CSR adjacency: no per-particle lists, 4 bytes per
  // element slot.
  const Adjacency adj = build_adjacency(element_vertices, arity, static_cast<int>(movable.size()));
  std::vector<int> color(elements, -1);
  std::vector<int> taken_by;  // taken_by[c] == e: color c is used next to element e
  int color_count = 0;
  for (int e = 0; e < elements; ++e) {
    for (int k = 0; k < arity; ++k) {
      const int v = element_vertices[e * arity + k];
      if (!movable[v]) continue;
      for (int f : adj.of(v)) {
        if (color[f] >= 0) taken_by[color[f]] = e;
      }
    }
    color[e] = first_free_color(taken_by, e);
    color_count = static_cast<int>(taken_by.size());
  }

  auto min_vertex = [&](int e) {
    return *std::min_element(element_vertices.begin() + e * arity, element_vertices.begin() + (e + 1) * arity);
  };
  ColorBlocks blocks;
  blocks.order.resize(elements);
  std::iota(blocks.order.begin(), blocks.order.end(), 0);
  std::stable_sort(blocks.order.begin(), blocks.order.end(), [&](int a, int b) {
    if (color[a] != color[b]) return color[a] < color[b];
    return min_vertex(a) < min_vertex(b);
  });
  blocks.offsets.assign(color_count + 1, 0);
  for (int e = 0; e < elements; ++e) ++blocks.offsets[color[e] + 1];
  std::partial_sum(blocks.offsets.begin(), blocks.offsets.end(), blocks.offsets.begin());
  return blocks;
}

}  // namespace atssim::graph
