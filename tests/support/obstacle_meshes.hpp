#pragma once
// Small triangle meshes for the obstacle tests: an icosphere (closed,
// convex, outward) and a flat sheet (open), and an OBJ writer.
#include <algorithm>
#include <array>
#include <cmath>
#include <fstream>
#include <limits>
#include <map>
#include <string>
#include <utility>
#include <vector>

#include <Eigen/Core>
#include <Eigen/Geometry>

#include "scene/collider_desc.hpp"

namespace atssim::test {

struct SimpleMesh {
  std::vector<std::array<double, 3>> vertices;
  std::vector<std::array<int, 3>> triangles;
};

// A mesh collider of m as a scene places it: scaled, turned by `deg`
// (about x, then y, then z), at `position`.
inline scene::ColliderDesc mesh_collider(const SimpleMesh& m, const Eigen::Vector3d& scale, const Eigen::Vector3d& deg,
                                         const Eigen::Vector3d& position, double thickness) {
  scene::ColliderDesc d;
  d.shape = scene::ColliderShape::mesh;
  d.mesh_vertices = m.vertices;
  d.mesh_triangles = m.triangles;
  d.scale = {scale.x(), scale.y(), scale.z()};
  d.rotate_deg = {deg.x(), deg.y(), deg.z()};
  d.point = {position.x(), position.y(), position.z()};
  d.thickness = thickness;
  return d;
}

// (Not curved_meshes.hpp's icosphere: one name, two inline functions, would break the ODR.)
// The icosahedron subdivided `levels` times, vertices on the sphere of
// `radius` about the origin; triangles counter-clockwise seen from outside.
inline SimpleMesh obstacle_icosphere(double radius, int levels) {
  const double t = (1.0 + std::sqrt(5.0)) / 2.0;
  SimpleMesh m;
  m.vertices = {{-1, t, 0},  {1, t, 0},  {-1, -t, 0}, {1, -t, 0}, {0, -1, t},  {0, 1, t},
                {0, -1, -t}, {0, 1, -t}, {t, 0, -1},  {t, 0, 1},  {-t, 0, -1}, {-t, 0, 1}};
  m.triangles = {{0, 11, 5},  {0, 5, 1},  {0, 1, 7},  {0, 7, 10}, {0, 10, 11}, {1, 5, 9}, {5, 11, 4},
                 {11, 10, 2}, {10, 7, 6}, {7, 1, 8},  {3, 9, 4},  {3, 4, 2},   {3, 2, 6}, {3, 6, 8},
                 {3, 8, 9},   {4, 9, 5},  {2, 4, 11}, {6, 2, 10}, {8, 6, 7},   {9, 8, 1}};
  const auto unit = [](std::array<double, 3> v) {
    const double n = std::sqrt(v[0] * v[0] + v[1] * v[1] + v[2] * v[2]);
    return std::array<double, 3>{v[0] / n, v[1] / n, v[2] / n};
  };
  for (auto& v : m.vertices) v = unit(v);
  for (int l = 0; l < levels; ++l) {
    std::map<std::pair<int, int>, int> mid;
    const auto middle = [&](int a, int b) {
      const auto key = std::minmax(a, b);
      if (auto it = mid.find(key); it != mid.end()) return it->second;
      const auto& p = m.vertices[a];
      const auto& q = m.vertices[b];
      m.vertices.push_back(unit({p[0] + q[0], p[1] + q[1], p[2] + q[2]}));
      return mid[key] = static_cast<int>(m.vertices.size()) - 1;
    };
    std::vector<std::array<int, 3>> next;
    for (const auto& f : m.triangles) {
      const int a = middle(f[0], f[1]), b = middle(f[1], f[2]), c = middle(f[2], f[0]);
      next.push_back({f[0], a, c});
      next.push_back({f[1], b, a});
      next.push_back({f[2], c, b});
      next.push_back({a, b, c});
    }
    m.triangles = next;
  }
  for (auto& v : m.vertices) v = {radius * v[0], radius * v[1], radius * v[2]};
  return m;
}

// n x n quads of side `size`/n in the xz plane at y = 0, centred on the origin.
inline SimpleMesh sheet(double size, int n) {
  SimpleMesh m;
  for (int i = 0; i <= n; ++i) {
    for (int j = 0; j <= n; ++j)
      m.vertices.push_back({size * (double(i) / n - 0.5), 0.0, size * (double(j) / n - 0.5)});
  }
  for (int i = 0; i < n; ++i) {
    for (int j = 0; j < n; ++j) {
      const int a = i * (n + 1) + j, b = a + 1, c = a + n + 1, d = c + 1;
      m.triangles.push_back({a, b, d});
      m.triangles.push_back({a, d, c});
    }
  }
  return m;
}

// An independent point-triangle distance (not the kernels' header): the
// plane's distance when the projection falls inside the triangle, else the
// nearest of its three edges.
inline double segment_distance(const Eigen::Vector3d& p, const Eigen::Vector3d& a, const Eigen::Vector3d& b) {
  const double t = std::clamp((p - a).dot(b - a) / (b - a).squaredNorm(), 0.0, 1.0);
  return (p - (a + t * (b - a))).norm();
}

inline double triangle_distance(const Eigen::Vector3d& p, const Eigen::Vector3d& a, const Eigen::Vector3d& b,
                                const Eigen::Vector3d& c) {
  const Eigen::Vector3d n = (b - a).cross(c - a).normalized();
  const Eigen::Vector3d q = p - n.dot(p - a) * n;
  const bool inside =
      (b - a).cross(q - a).dot(n) >= 0 && (c - b).cross(q - b).dot(n) >= 0 && (a - c).cross(q - c).dot(n) >= 0;
  if (inside) return std::abs(n.dot(p - a));
  return std::min({segment_distance(p, a, b), segment_distance(p, b, c), segment_distance(p, c, a)});
}

// Brute force over every triangle of `m` moved by `offset`.
inline double mesh_distance(const SimpleMesh& m, const Eigen::Vector3d& offset, const Eigen::Vector3d& p) {
  double d = std::numeric_limits<double>::infinity();
  const auto at = [&](int i) -> Eigen::Vector3d {
    return Eigen::Vector3d(m.vertices[i][0], m.vertices[i][1], m.vertices[i][2]) + offset;
  };
  for (const auto& t : m.triangles) d = std::min(d, triangle_distance(p, at(t[0]), at(t[1]), at(t[2])));
  return d;
}

inline void write_obj(const std::string& path, const SimpleMesh& m) {
  std::ofstream out(path);
  out.precision(17);
  for (const auto& v : m.vertices) out << "v " << v[0] << ' ' << v[1] << ' ' << v[2] << '\n';
  for (const auto& t : m.triangles) out << "f " << t[0] + 1 << ' ' << t[1] + 1 << ' ' << t[2] + 1 << '\n';
}

}  // namespace atssim::test
