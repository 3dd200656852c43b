#include "solver/energy/element_math.hpp"  // first: the double instance of the shared math

#include "solver/energy/sheet_neighbours.hpp"

#include <algorithm>

namespace atssim::solver::energy {

namespace {

f64::ats_vec3 v3(const Eigen::Vector3d& p) { return f64::ats_v3(p.x(), p.y(), p.z()); }

bool in_plane(const Eigen::Vector3d& diff, const std::array<int, 3>& f, const SheetNeighbours::Positions& at) {
  return f64::ats_pair_in_plane(v3(diff), v3(at(f[0])), v3(at(f[1])), v3(at(f[2])));
}

}  // namespace

SheetNeighbours::SheetNeighbours(const std::vector<std::array<int, 3>>& tris) : tris_(tris) {
  int n = 0;
  for (const auto& f : tris_) n = std::max({n, f[0] + 1, f[1] + 1, f[2] + 1});
  incident_.resize(static_cast<std::size_t>(n));
  for (std::size_t t = 0; t < tris_.size(); ++t)
    for (int v : tris_[t]) incident_[v].push_back(static_cast<int>(t));
}

bool SheetNeighbours::vertex_triangle(int v, const std::array<int, 3>& f, const Eigen::Vector3d& diff,
                                      const Positions& at) const {
  return in_plane(diff, f, at) && joined(v, f);
}

bool SheetNeighbours::edge_edge(const std::array<int, 2>& a, const std::array<int, 2>& b, const Eigen::Vector3d& diff,
                                const Positions& at) const {
  const std::array<int, 3> ends{b[0], b[1], b[1]};
  return (joined(a[0], ends) || joined(a[1], ends)) && edge_in_plane(a, diff, at) && edge_in_plane(b, diff, at);
}

bool SheetNeighbours::joined(int v, const std::array<int, 3>& c) const {
  if (v < 0 || v >= static_cast<int>(incident_.size())) return false;
  return std::any_of(incident_[v].begin(), incident_[v].end(), [&](int t) {
    return std::any_of(tris_[t].begin(), tris_[t].end(), [&](int w) { return w == c[0] || w == c[1] || w == c[2]; });
  });
}

bool SheetNeighbours::edge_in_plane(const std::array<int, 2>& e, const Eigen::Vector3d& diff,
                                    const Positions& at) const {
  return std::all_of(incident_[e[0]].begin(), incident_[e[0]].end(), [&](int t) {
    const auto& f = tris_[t];
    const bool of_edge = f[0] == e[1] || f[1] == e[1] || f[2] == e[1];
    return !of_edge || in_plane(diff, f, at);
  });
}

}  // namespace atssim::solver::energy
