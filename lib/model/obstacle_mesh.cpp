#include "model/obstacle_mesh.hpp"

#include <algorithm>
#include <cmath>
#include <map>
#include <utility>

#include <Eigen/Geometry>

#include "util/error.hpp"

namespace atssim::model {

namespace {

using Edge = std::pair<int, int>;

// Closed: every undirected edge is run once in each direction.
bool is_closed(const std::vector<std::array<int, 3>>& tris) {
  std::map<Edge, int> directed;
  for (const auto& t : tris) {
    for (int k = 0; k < 3; ++k) ++directed[{t[k], t[(k + 1) % 3]}];
  }
  for (const auto& [e, n] : directed) {
    if (n != 1) return false;
    const auto back = directed.find({e.second, e.first});
    if (back == directed.end() || back->second != 1) return false;
  }
  return !tris.empty();
}

double signed_volume(const std::vector<Eigen::Vector3d>& v, const std::vector<std::array<int, 3>>& tris) {
  double six_v = 0.0;
  for (const auto& t : tris) six_v += v[t[0]].dot(v[t[1]].cross(v[t[2]]));
  return six_v / 6.0;
}

void pseudo_normals(ObstacleMesh& m) {
  const auto& v = m.vertices;
  m.face_normal.clear();
  m.vertex_normal.assign(v.size(), Eigen::Vector3d::Zero());
  std::map<Edge, Eigen::Vector3d> edge_sum;  // undirected
  for (const auto& t : m.triangles) {
    const Eigen::Vector3d n = (v[t[1]] - v[t[0]]).cross(v[t[2]] - v[t[0]]).normalized();
    m.face_normal.push_back(n);
    for (int k = 0; k < 3; ++k) {
      const Eigen::Vector3d e1 = (v[t[(k + 1) % 3]] - v[t[k]]).normalized();
      const Eigen::Vector3d e2 = (v[t[(k + 2) % 3]] - v[t[k]]).normalized();
      const double angle = std::acos(std::clamp(e1.dot(e2), -1.0, 1.0));
      m.vertex_normal[t[k]] += angle * n;
      const Edge e = std::minmax(t[k], t[(k + 1) % 3]);
      edge_sum.try_emplace(e, Eigen::Vector3d::Zero()).first->second += n;
    }
  }
  for (auto& n : m.vertex_normal) n = n.squaredNorm() > 0.0 ? n.normalized() : Eigen::Vector3d::UnitY();
  m.edge_normal.clear();
  for (std::size_t i = 0; i < m.triangles.size(); ++i) {
    const auto& t = m.triangles[i];
    std::array<Eigen::Vector3d, 3> e;
    for (int k = 0; k < 3; ++k) {
      const Eigen::Vector3d s = edge_sum.at(std::minmax(t[k], t[(k + 1) % 3]));
      e[k] = s.squaredNorm() > 1e-24 ? s.normalized() : m.face_normal[i];
    }
    m.edge_normal.push_back(e);
  }
}

}  // namespace

ObstacleMesh make_obstacle_mesh(const std::vector<std::array<double, 3>>& vertices,
                                const std::vector<std::array<int, 3>>& triangles, const std::array<double, 3>& scale) {
  ObstacleMesh m;
  for (const auto& p : vertices) m.vertices.emplace_back(p[0] * scale[0], p[1] * scale[1], p[2] * scale[2]);
  for (const auto& t : triangles) {
    const Eigen::Vector3d a = m.vertices[t[0]], b = m.vertices[t[1]], c = m.vertices[t[2]];
    if ((b - a).cross(c - a).squaredNorm() > 0.0) m.triangles.push_back(t);
  }
  // The scene reader refuses such a file with its line; this guards other callers.
  if (m.triangles.empty()) throw input_error("a mesh obstacle needs at least one triangle of non-zero area");
  m.closed = is_closed(m.triangles);
  if (m.closed && signed_volume(m.vertices, m.triangles) < 0.0) {
    for (auto& t : m.triangles) std::swap(t[1], t[2]);
  }
  pseudo_normals(m);
  m.bvh = build_bvh(m.vertices, m.triangles);
  return m;
}

}  // namespace atssim::model
