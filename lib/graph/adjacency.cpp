#include "graph/adjacency.hpp"

#include <numeric>

#include <fmt/format.h>

#include "util/error.hpp"

namespace atssim::graph {

Adjacency build_adjacency(std::span<const int> element_vertices, int arity, int particle_count) {
  if (arity <= 0 || element_vertices.size() % static_cast<std::size_t>(arity) != 0) {
    throw internal_error(
        fmt::format("adjacency: {} indices do not form elements of {} vertices", element_vertices.size(), arity));
  }
  Adjacency adj;
  std::vector<int> count(particle_count + 1, 0);
  for (int v : element_vertices) {
    if (v < 0 || v >= particle_count) {
      throw internal_error(fmt::format("adjacency: vertex {} outside 0..{}", v, particle_count - 1));
    }
    ++count[v];
  }
  adj.offsets.resize(particle_count + 1);
  std::exclusive_scan(count.begin(), count.end(), adj.offsets.begin(), 0);
  adj.elements.resize(element_vertices.size());
  std::vector<int> cursor(adj.offsets.begin(), adj.offsets.end() - 1);
  const int elements = static_cast<int>(element_vertices.size()) / arity;
  for (int e = 0; e < elements; ++e) {
    for (int k = 0; k < arity; ++k) adj.elements[cursor[element_vertices[e * arity + k]]++] = e;
  }
  return adj;
}

}  // namespace atssim::graph
