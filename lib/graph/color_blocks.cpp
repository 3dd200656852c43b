#include "graph/color_blocks.hpp"

#include <algorithm>
#include <numeric>

namespace atssim::graph {

ColorBlocks color_elements(std::span<const int> element_vertices, int arity, std::span<const char> movable) {
  const int elements = static_cast<int>(element_vertices.size()) / arity;
  std::vector<std::vector<int>> used(movable.size());  // colors taken at each particle
  std::vector<int> color(elements, 0);
  std::vector<char> taken;
  int color_count = 0;
  for (int e = 0; e < elements; ++e) {
    taken.assign(color_count + 1, 0);
    for (int k = 0; k < arity; ++k) {
      const int v = element_vertices[e * arity + k];
      if (!movable[v]) continue;
      for (int c : used[v]) taken[c] = 1;
    }
    const int c = static_cast<int>(std::find(taken.begin(), taken.end(), 0) - taken.begin());
    color[e] = c;
    color_count = std::max(color_count, c + 1);
    for (int k = 0; k < arity; ++k) {
      const int v = element_vertices[e * arity + k];
      if (movable[v]) used[v].push_back(c);
    }
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
