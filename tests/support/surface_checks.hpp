#pragma once
// An independent checker of simulated surfaces for the contact tests,
// written here in double (not the kernels' headers): point-triangle
// distance, segment-triangle crossing, and over a whole surface the
// closest non-incident vertex-triangle pair and the edges that pass
// through triangles they do not touch (a uniform grid culls the pairs).
#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <limits>
#include <map>
#include <unordered_map>
#include <utility>
#include <vector>

#include <Eigen/Core>
#include <Eigen/Geometry>

#include "model/model.hpp"

namespace atssim::test {

inline double point_segment(const Eigen::Vector3d& p, const Eigen::Vector3d& a, const Eigen::Vector3d& b) {
  const Eigen::Vector3d ab = b - a;
  const double len2 = ab.squaredNorm();
  const double t = len2 > 0.0 ? std::clamp((p - a).dot(ab) / len2, 0.0, 1.0) : 0.0;
  return (p - (a + t * ab)).norm();
}

// Distance to the plane when the projection falls inside (three edge-side
// tests), else to the nearest edge.
inline double point_triangle(const Eigen::Vector3d& p, const Eigen::Vector3d& a, const Eigen::Vector3d& b,
                             const Eigen::Vector3d& c) {
  const Eigen::Vector3d n = (b - a).cross(c - a);
  const double area2 = n.norm();
  const double edges = std::min({point_segment(p, a, b), point_segment(p, b, c), point_segment(p, c, a)});
  if (!(area2 > 1e-14)) return edges;
  const Eigen::Vector3d u = n / area2;
  const Eigen::Vector3d q = p - (p - a).dot(u) * u;
  const bool inside =
      (b - a).cross(q - a).dot(n) >= 0.0 && (c - b).cross(q - b).dot(n) >= 0.0 && (a - c).cross(q - c).dot(n) >= 0.0;
  return inside ? std::abs((p - a).dot(u)) : edges;
}

// Whether segment pq passes through triangle abc (Möller-Trumbore, both
// ends strictly on either side of the plane).
inline bool segment_crosses(const Eigen::Vector3d& p, const Eigen::Vector3d& q, const Eigen::Vector3d& a,
                            const Eigen::Vector3d& b, const Eigen::Vector3d& c) {
  const Eigen::Vector3d n = (b - a).cross(c - a);
  const double sp = (p - a).dot(n), sq = (q - a).dot(n);
  if (sp * sq >= 0.0) return false;
  const Eigen::Vector3d x = p + (sp / (sp - sq)) * (q - p);
  return (b - a).cross(x - a).dot(n) >= 0.0 && (c - b).cross(x - b).dot(n) >= 0.0 && (a - c).cross(x - c).dot(n) >= 0.0;
}

// Every object's triangles (a solid's: its boundary faces) and their unique
// edges, in global vertex numbers.
struct Surface {
  std::vector<std::array<int, 3>> tris;
  std::vector<std::array<int, 2>> edges;
};

inline Surface surface_of(const model::Model& m) {
  Surface s;
  std::map<std::pair<int, int>, int> seen;
  for (const model::ObjectRange& o : m.objects) {
    for (const auto& t : o.triangles) {
      const std::array<int, 3> g{t[0] + o.vertex_offset, t[1] + o.vertex_offset, t[2] + o.vertex_offset};
      s.tris.push_back(g);
      for (int k = 0; k < 3; ++k) {
        const std::pair<int, int> e{std::min(g[k], g[(k + 1) % 3]), std::max(g[k], g[(k + 1) % 3])};
        if (seen.emplace(e, 0).second) s.edges.push_back({e.first, e.second});
      }
    }
  }
  return s;
}

struct SurfaceReport {
  double closest = std::numeric_limits<double>::infinity();  // non-incident vertex-triangle, within `reach`
  int crossings = 0;                                         // edges through triangles they do not touch
};

// Closest non-incident vertex-triangle distance (pairs farther than
// `reach` are not looked at: closest stays infinite) and crossings, over a
// uniform grid whose cells are at least the longest edge.
inline SurfaceReport check_surface(const Surface& s, const std::vector<Eigen::Vector3d>& x, double reach) {
  SurfaceReport out;
  if (s.tris.empty()) return out;
  double cell = reach;
  for (const auto& e : s.edges) cell = std::max(cell, (x[e[0]] - x[e[1]]).norm());
  const auto key = [&](const Eigen::Vector3d& p) {
    const auto f = [&](double v) { return static_cast<std::int64_t>(std::floor(v / cell)) & 0x1fffff; };
    return (f(p.x()) << 42) | (f(p.y()) << 21) | f(p.z());
  };
  std::unordered_map<std::int64_t, std::vector<int>> grid;
  for (int t = 0; t < int(s.tris.size()); ++t) {
    Eigen::Vector3d lo = x[s.tris[t][0]], hi = lo;
    for (int k = 1; k < 3; ++k) {
      lo = lo.cwiseMin(x[s.tris[t][k]]);
      hi = hi.cwiseMax(x[s.tris[t][k]]);
    }
    lo.array() -= reach;
    hi.array() += reach;
    for (double i = std::floor(lo.x() / cell); i <= std::floor(hi.x() / cell); ++i)
      for (double j = std::floor(lo.y() / cell); j <= std::floor(hi.y() / cell); ++j)
        for (double k = std::floor(lo.z() / cell); k <= std::floor(hi.z() / cell); ++k)
          grid[key(Eigen::Vector3d((i + 0.5) * cell, (j + 0.5) * cell, (k + 0.5) * cell))].push_back(t);
  }
  const auto touches = [](const std::array<int, 3>& t, int v) { return v == t[0] || v == t[1] || v == t[2]; };
  for (int v = 0; v < int(x.size()); ++v) {
    const auto it = grid.find(key(x[v]));
    if (it == grid.end()) continue;
    for (int t : it->second) {
      const auto& tri = s.tris[t];
      if (touches(tri, v)) continue;
      const double d = point_triangle(x[v], x[tri[0]], x[tri[1]], x[tri[2]]);
      if (d <= reach) out.closest = std::min(out.closest, d);
    }
  }
  std::vector<int> stamp(s.tris.size(), -1);
  for (int e = 0; e < int(s.edges.size()); ++e) {
    const Eigen::Vector3d &p = x[s.edges[e][0]], &q = x[s.edges[e][1]];
    // The cells the edge's box meets (at most 2 x 2 x 2: an edge is no
    // longer than a cell) hold every triangle whose grown box it meets.
    const Eigen::Vector3d lo = p.cwiseMin(q), hi = p.cwiseMax(q);
    for (double i = std::floor(lo.x() / cell); i <= std::floor(hi.x() / cell); ++i)
      for (double j = std::floor(lo.y() / cell); j <= std::floor(hi.y() / cell); ++j)
        for (double k = std::floor(lo.z() / cell); k <= std::floor(hi.z() / cell); ++k) {
          const auto it = grid.find(key(Eigen::Vector3d((i + 0.5) * cell, (j + 0.5) * cell, (k + 0.5) * cell)));
          if (it == grid.end()) continue;
          for (int t : it->second) {
            if (stamp[t] == e) continue;
            stamp[t] = e;
            const auto& tri = s.tris[t];
            if (touches(tri, s.edges[e][0]) || touches(tri, s.edges[e][1])) continue;
            if (segment_crosses(p, q, x[tri[0]], x[tri[1]], x[tri[2]])) ++out.crossings;
          }
        }
  }
  return out;
}

}  // namespace atssim::test
