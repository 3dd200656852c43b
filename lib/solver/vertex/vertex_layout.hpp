#pragma once
// What vertex-block methods (VBD, JPGD) add to the cloth layout: for every
// particle, the elements that touch it (a CSR list, built NvCloth's way:
// count, prefix sum, fill), and a vertex coloring for Gauss-Seidel sweeps.
#include <vector>

#include "graph/color_blocks.hpp"
#include "solver/layout/sim_layout.hpp"

namespace atssim::solver::vertex {

struct VertexLayout {
  std::vector<int> adjacency_offsets;  // particles + 1
  std::vector<int> adjacency;          // element << 4 | kind << 2 | slot (kind 0 stretch, 1 bending, 2 tet)
  graph::ColorBlocks colors;           // movable particles only
};

VertexLayout make_vertex_layout(const SimLayout& layout);

// The colors cut into batches of kLaneWidth vertices (VBD's solver.ordering:
// color_batches, kernels/common/vertex_system_lanes.h): each color's
// vertices in their order, padded with -1 to a whole batch; batch b is
// order[kLaneWidth b … kLaneWidth b + kLaneWidth), and color c's batches are
// [offsets[c], offsets[c + 1]).
inline constexpr int kLaneWidth = 8;
struct ColorLanes {
  std::vector<int> order;
  std::vector<int> offsets;
};
ColorLanes color_lanes(const graph::ColorBlocks& colors);

// Entry code of kernels/common/vertex_system.cl.
inline int adjacency_code(int element, int kind, int slot) { return element << 4 | kind << 2 | slot; }

}  // namespace atssim::solver::vertex
