#include "graph/vertex_colors.hpp"

#include <algorithm>
#include <numeric>

#include "graph/greedy_color.hpp"

namespace atssim::graph {

ColorBlocks color_vertices(std::span<const ElementSet> sets, std::span<const char> movable) {
  const int n = static_cast<int>(movable.size());
  std::vector<Adjacency> adjacency;
  for (const ElementSet& s : sets) adjacency.push_back(build_adjacency(s.vertices, s.arity, n));

  std::vector<int> color(n, -1);
  std::vector<int> taken_by;  // taken_by[c] == v: color c is used next to v
  int colors = 0;
  for (int v = 0; v < n; ++v) {
    if (!movable[v]) continue;
    for (std::size_t k = 0; k < sets.size(); ++k) {
      const ElementSet& s = sets[k];
      for (int e : adjacency[k].of(v)) {
        for (int j = 0; j < s.arity; ++j) {
          const int u = s.vertices[e * s.arity + j];
          if (u != v && color[u] >= 0) taken_by[color[u]] = v;
        }
      }
    }
    color[v] = first_free_color(taken_by, v);
    colors = static_cast<int>(taken_by.size());
  }
  ColorBlocks blocks;
  blocks.offsets.assign(colors + 1, 0);
  for (int v = 0; v < n; ++v) {
    if (color[v] >= 0) ++blocks.offsets[color[v] + 1];
  }
  std::partial_sum(blocks.offsets.begin(), blocks.offsets.end(), blocks.offsets.begin());
  blocks.order.resize(blocks.offsets.back());
  std::vector<int> cursor(blocks.offsets.begin(), blocks.offsets.end() - 1);
  for (int v = 0; v < n; ++v) {
    if (color[v] >= 0) blocks.order[cursor[color[v]]++] = v;  // ascending v: each block sorted
  }
  return blocks;
}

}  // namespace atssim::graph
