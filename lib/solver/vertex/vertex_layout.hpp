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

// Entry code of kernels/common/vertex_system.cl.
inline int adjacency_code(int element, int kind, int slot) { return element << 4 | kind << 2 | slot; }

}  // namespace atssim::solver::vertex
