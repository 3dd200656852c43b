#include "solver/layout/particle_tables.hpp"

namespace atssim::solver {

namespace {

template <typename Element, int Arity, typename Vertex>
std::shared_ptr<const std::vector<std::int32_t>> table(const std::vector<Element>& elements, Vertex vertex) {
  auto out = std::make_shared<std::vector<std::int32_t>>();
  out->reserve(elements.size() * Arity);
  for (const Element& e : elements) {
    for (int k = 0; k < Arity; ++k) out->push_back(vertex(e, k));
  }
  return out;
}

}  // namespace

std::shared_ptr<const std::vector<std::int32_t>> particles_of(const std::vector<ats_distance_c>& stretch) {
  return table<ats_distance_c, 2>(stretch, [](const ats_distance_c& c, int k) { return k == 0 ? c.a : c.b; });
}

std::shared_ptr<const std::vector<std::int32_t>> particles_of(const std::vector<ats_bend_c>& bend) {
  return table<ats_bend_c, 4>(bend, [](const ats_bend_c& c, int k) { return c.v[k]; });
}

std::shared_ptr<const std::vector<std::int32_t>> particles_of(const std::vector<ats_tet_c>& tets) {
  return table<ats_tet_c, 4>(tets, [](const ats_tet_c& t, int k) { return t.v[k]; });
}

}  // namespace atssim::solver
