#pragma once
// Particle -> element adjacency in CSR form, built NvCloth's way
// (AdjacencyQuerier): count elements per particle, exclusive prefix sum into
// n + 1 offsets, then fill. Particle p's elements are
// elements[offsets[p] .. offsets[p + 1]).
#include <span>
#include <vector>

namespace atssim::graph {

struct Adjacency {
  std::vector<int> offsets;   // particle_count + 1 entries
  std::vector<int> elements;  // element ids, ascending within each particle
  std::span<const int> of(int particle) const {
    return std::span<const int>(elements).subspan(offsets[particle], offsets[particle + 1] - offsets[particle]);
  }
};

// `element_vertices` holds `arity` particle indices per element, flat.
Adjacency build_adjacency(std::span<const int> element_vertices, int arity, int particle_count);

}  // namespace atssim::graph
