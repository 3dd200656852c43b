#include "solver/vertex/vertex_layout.hpp"

#include "graph/adjacency.hpp"
#include "graph/vertex_colors.hpp"

namespace atssim::solver::vertex {

VertexLayout make_vertex_layout(const SimLayout& layout) {
  const int n = static_cast<int>(layout.x.size());
  std::vector<int> stretch_vertices, bend_vertices, tet_vertices;
  for (const auto& c : layout.stretch) stretch_vertices.insert(stretch_vertices.end(), {c.a, c.b});
  for (const auto& c : layout.bend) bend_vertices.insert(bend_vertices.end(), c.v, c.v + 4);
  for (const auto& c : layout.tets) tet_vertices.insert(tet_vertices.end(), c.v, c.v + 4);

  const graph::Adjacency by_stretch = graph::build_adjacency(stretch_vertices, 2, n);
  const graph::Adjacency by_bend = graph::build_adjacency(bend_vertices, 4, n);
  const graph::Adjacency by_tet = graph::build_adjacency(tet_vertices, 4, n);
  VertexLayout out;
  out.adjacency_offsets.assign(n + 1, 0);
  for (int i = 0; i < n; ++i) {
    out.adjacency_offsets[i + 1] =
        out.adjacency_offsets[i] +
        static_cast<int>(by_stretch.of(i).size() + by_bend.of(i).size() + by_tet.of(i).size());
  }
  out.adjacency.reserve(out.adjacency_offsets.back());
  for (int i = 0; i < n; ++i) {
    for (int e : by_stretch.of(i)) out.adjacency.push_back(adjacency_code(e, 0, stretch_vertices[2 * e] == i ? 0 : 1));
    for (int e : by_bend.of(i)) {
      int slot = 0;
      while (bend_vertices[4 * e + slot] != i) ++slot;
      out.adjacency.push_back(adjacency_code(e, 1, slot));
    }
    for (int e : by_tet.of(i)) {
      int slot = 0;
      while (tet_vertices[4 * e + slot] != i) ++slot;
      out.adjacency.push_back(adjacency_code(e, 2, slot));
    }
  }
  std::vector<char> movable(n);
  for (int i = 0; i < n; ++i) movable[i] = layout.x[i].w > 0.0f;
  const graph::ElementSet sets[] = {{stretch_vertices, 2}, {bend_vertices, 4}, {tet_vertices, 4}};
  out.colors = graph::color_vertices(sets, movable);
  return out;
}

ColorLanes color_lanes(const graph::ColorBlocks& colors) {
  ColorLanes out;
  out.offsets.push_back(0);
  for (int c = 0; c < colors.count(); ++c) {
    const std::span<const int> block = colors.block(c);
    out.order.insert(out.order.end(), block.begin(), block.end());
    out.order.resize((out.order.size() + kLaneWidth - 1) / kLaneWidth * kLaneWidth, -1);
    out.offsets.push_back(static_cast<int>(out.order.size()) / kLaneWidth);
  }
  return out;
}

std::vector<int> vertex_lanes(int n) {
  std::vector<int> order((n + kLaneWidth - 1) / kLaneWidth * kLaneWidth, -1);
  for (int i = 0; i < n; ++i) order[i] = i;
  return order;
}

}  // namespace atssim::solver::vertex
