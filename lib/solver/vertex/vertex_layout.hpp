#pragma once
// What vertex-block methods (VBD, JPGD) add to the cloth layout: for every
// particle, the elements that touch it (a CSR list, built NvCloth's way:
// count, prefix sum, fill), and a vertex coloring for Gauss-Seidel sweeps.
#include <string_view>
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
// The Jacobi methods' (JPGD, SOSD) solver.ordering, whose vertices all read
// the same positions: vertices runs a work-item per vertex; vertex_batches
// a work-item per kLaneWidth consecutive vertices whose element sums run as
// float lanes (kernels/common/vertex_system_lanes.h), the same bits.
// colors and color_batches, XPBD's and VBD's names for the one-element and
// the lanes orderings, mean the same, so that a scene written for those
// methods runs under these (the choice's index modulo 2).
enum class JacobiOrdering { vertices, vertex_batches };  // solver.ordering's choices in order
inline constexpr std::string_view kJacobiOrderings[] = {"vertices", "vertex_batches", "colors", "color_batches"};
inline JacobiOrdering jacobi_ordering(double choice) {
  return static_cast<JacobiOrdering>(static_cast<int>(choice) % 2);
}

// Vertices 0 … n - 1 in batches of kLaneWidth, padded with -1 to a whole
// batch (vertex_batches): ceil(n / kLaneWidth) batches.
std::vector<int> vertex_lanes(int n);

// Entry code of kernels/common/vertex_system.cl.
inline int adjacency_code(int element, int kind, int slot) { return element << 4 | kind << 2 | slot; }

}  // namespace atssim::solver::vertex
