#pragma once
// Greedy coloring of particles so that no two particles of one color share
// an element: each color is a block of vertices that vertex-block methods
// (VBD, Chen et al. 2024) update in parallel inside a Gauss-Seidel sweep.
// Particles that cannot move are left out of every block.
#include <span>
#include <vector>

#include "graph/adjacency.hpp"
#include "graph/color_blocks.hpp"

namespace atssim::graph {

struct ElementSet {
  std::span<const int> vertices;  // `arity` particle indices per element, flat
  int arity = 0;
};

// `order` of the result holds particle ids grouped by color, each block
// sorted by index.
ColorBlocks color_vertices(std::span<const ElementSet> sets, std::span<const char> movable);

}  // namespace atssim::graph
