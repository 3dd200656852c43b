#include "solver/energy/element_math.hpp"  // first: the double instance of the shared math

#include "solver/contact/surface_contacts.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <set>
#include <stdexcept>
#include <utility>

#include <fmt/format.h>
#include <tbb/blocked_range.h>
#include <tbb/parallel_reduce.h>

#include "solver/contact/box_grid.hpp"

namespace atssim::solver {

namespace {

using Box = BoxGrid::Box;
using Eigen::Vector3d;
namespace f64 = energy::f64;

f64::ats_vec3 v3(const Vector3d& p) { return f64::ats_v3(p.x(), p.y(), p.z()); }

// What one stretch of vertices or edges found.
struct Tally {
  int vertex_triangle = 0, edge_edge = 0, crossings = 0;
  double closest = std::numeric_limits<double>::infinity();
};

Tally joined(Tally a, const Tally& b) {
  a.vertex_triangle += b.vertex_triangle;
  a.edge_edge += b.edge_edge;
  a.crossings += b.crossings;
  a.closest = std::min(a.closest, b.closest);
  return a;
}

template <std::size_t N>
Box box_of(const std::array<int, N>& v, const std::vector<Vector3d>& x, double widen) {
  Box b(x[v[0]]);
  for (std::size_t k = 1; k < N; ++k) b.extend(x[v[k]]);
  b.min().array() -= widen;
  b.max().array() += widen;
  return b;
}

bool shares_vertex(const std::array<int, 2>& e, const std::array<int, 3>& t) {
  return e[0] == t[0] || e[0] == t[1] || e[0] == t[2] || e[1] == t[0] || e[1] == t[1] || e[1] == t[2];
}

// Six times the signed volume of the tetrahedron (u, v, w, z).
double volume(const Vector3d& u, const Vector3d& v, const Vector3d& w, const Vector3d& z) {
  return (v - u).cross(w - u).dot(z - u);
}

// segment_crosses_triangle with the triangle's normal n = (b − a) × (c − a)
// given (measure() computes it once per triangle).
bool crosses(const Vector3d& p, const Vector3d& q, const Vector3d& a, const Vector3d& b, const Vector3d& c,
             const Vector3d& n) {
  const double vp = n.dot(p - a), vq = n.dot(q - a);
  if (!((vp > 0 && vq < 0) || (vp < 0 && vq > 0))) return false;
  // The line pq passes inside or on the border of abc when it turns the
  // same way around all three of its edges.
  const double s0 = volume(p, q, a, b), s1 = volume(p, q, b, c), s2 = volume(p, q, c, a);
  return (s0 >= 0 && s1 >= 0 && s2 >= 0) || (s0 <= 0 && s1 <= 0 && s2 <= 0);
}

}  // namespace

SurfaceContactCheck::SurfaceContactCheck(std::vector<std::array<int, 3>> triangles, double thickness)
    : tris_(std::move(triangles)), sheet_(tris_), thickness_(thickness) {
  std::set<std::pair<int, int>> seen;
  std::set<int> vertices;
  own_vertices_.assign(tris_.size(), {-1, -1, -1});
  own_edges_.assign(tris_.size(), {-1, -1, -1});
  for (std::size_t t = 0; t < tris_.size(); ++t) {
    int owned_vertices = 0, owned_edges = 0;
    for (int k = 0; k < 3; ++k) {
      const int a = tris_[t][k], b = tris_[t][(k + 1) % 3];
      if (seen.emplace(std::min(a, b), std::max(a, b)).second) {
        own_edges_[t][owned_edges++] = static_cast<int>(edges_.size());
        edges_.push_back({std::min(a, b), std::max(a, b)});
      }
      if (vertices.insert(a).second) own_vertices_[t][owned_vertices++] = a;
    }
  }
  vertices_.assign(vertices.begin(), vertices.end());
}

SurfaceContacts SurfaceContactCheck::measure(std::span<const float> xyz) const {
  SurfaceContacts out;
  if (tris_.empty()) return out;
  const std::size_t n = xyz.size() / 3;
  if (static_cast<std::size_t>(vertices_.back()) >= n) {
    throw std::logic_error(
        fmt::format("surface contacts: the surface names particle {}, the state has {}", vertices_.back(), n));
  }
  std::vector<Vector3d> x(n);
  for (std::size_t i = 0; i < n; ++i) x[i] = Vector3d(xyz[3 * i], xyz[3 * i + 1], xyz[3 * i + 2]);
  const double r = thickness_;
  const energy::SheetNeighbours::Positions at = [&](int i) { return x[i]; };
  const auto finite = [](const Box& b) { return b.min().allFinite() && b.max().allFinite(); };

  // Triangle j's box in the grid holds the triangle and the edges it owns:
  // with a corner that is not finite, only its finite owned edges (a pair
  // with the triangle itself is then never closer than r nor a crossing).
  std::vector<Box> tri_boxes(tris_.size()), edge_boxes(edges_.size());
  for (std::size_t e = 0; e < edges_.size(); ++e) edge_boxes[e] = box_of(edges_[e], x, 0.0);
  std::vector<Vector3d> normal(tris_.size());
  for (std::size_t t = 0; t < tris_.size(); ++t) {
    const auto& f = tris_[t];
    normal[t] = (x[f[1]] - x[f[0]]).cross(x[f[2]] - x[f[0]]);
    tri_boxes[t] = box_of(f, x, 0.0);
    if (finite(tri_boxes[t])) continue;
    tri_boxes[t] = Box();  // empty: never reported
    for (int e : own_edges_[t])
      if (e >= 0 && finite(edge_boxes[e])) tri_boxes[t].extend(edge_boxes[e]);
  }
  // Per triangle u, its owned vertices against every triangle, its owned
  // edges against every edge (each pair once: from the lower edge id) and
  // against every triangle for a crossing: the triangles that overlap u's
  // query box, what it owns widened by r (within r of u's own box).
  const BoxGrid triangles(std::move(tri_boxes), r);
  struct Query {
    Box box;                   // the finite owned primitives, widened by r
    std::array<Box, 3> wide;   // each owned edge's box widened by r
    BoxGrid::FloatBox bounds;  // box's
  };
  const auto query_of = [&](int u) {
    Query q;
    for (int v : own_vertices_[u])
      if (v >= 0 && x[v].allFinite()) q.box.extend(x[v]);
    for (int k = 0; k < 3; ++k) {
      const int e = own_edges_[u][k];
      if (e < 0) continue;
      if (finite(edge_boxes[e])) q.box.extend(edge_boxes[e]);
      q.wide[k] = edge_boxes[e];
      q.wide[k].min().array() -= r;
      q.wide[k].max().array() += r;
    }
    if (!q.box.isEmpty()) {
      q.box.min().array() -= r;
      q.box.max().array() += r;
      q.bounds = BoxGrid::FloatBox::outward(q.box);
    }
    return q;
  };
  // Triangle u's owned primitives against triangle o, whose box overlaps u's query.
  const auto visit = [&](int u, const Query& q, int o, Tally& t) {
    const auto& own_v = own_vertices_[u];
    const auto& own_e = own_edges_[u];
    const auto& f = tris_[o];
    const Box& ob = triangles.box(o);
    for (int v : own_v) {
      if (v < 0 || v == f[0] || v == f[1] || v == f[2] || (ob.squaredExteriorDistance(x[v]) > r * r)) continue;
      const f64::ats_pair_geometry g = f64::ats_point_triangle(v3(x[v]), v3(x[f[0]]), v3(x[f[1]]), v3(x[f[2]]));
      const double d = g.d;
      if (d < r && !sheet_.vertex_triangle(v, f, {g.diff.x, g.diff.y, g.diff.z}, at)) {
        ++t.vertex_triangle;
        t.closest = std::min(t.closest, d);
      }
    }
    for (int k = 0; k < 3; ++k) {
      const int e = own_e[k];
      if (e < 0 || !q.wide[k].intersects(ob)) continue;
      const auto& a = edges_[e];
      for (int h : own_edges_[o]) {
        if (h <= e) continue;  // each pair once
        const auto& b = edges_[h];
        if (b[0] == a[0] || b[0] == a[1] || b[1] == a[0] || b[1] == a[1] || !q.wide[k].intersects(edge_boxes[h]))
          continue;
        const f64::ats_pair_geometry g = f64::ats_edge_edge(v3(x[a[0]]), v3(x[a[1]]), v3(x[b[0]]), v3(x[b[1]]));
        const double d = g.d;
        if (d < r && !sheet_.edge_edge(a, b, {g.diff.x, g.diff.y, g.diff.z}, at)) {
          ++t.edge_edge;
          t.closest = std::min(t.closest, d);
        }
      }
      if (!shares_vertex(a, f) && crosses(x[a[0]], x[a[1]], x[f[0]], x[f[1]], x[f[2]], normal[o])) ++t.crossings;
    }
  };
  // The triangles of one grid cell together: the boxes near their cell
  // listed once, and each triangle's query tested against that list (it
  // meets the same triangles as a query of the grid of its own would).
  const Tally all = tbb::parallel_reduce(
      tbb::blocked_range<int>(0, static_cast<int>(tris_.size()), 256), Tally{},
      [&](const tbb::blocked_range<int>& range, Tally t) {
        struct Candidate {
          BoxGrid::FloatBox bounds;
          int id;
        };
        std::vector<int> mates;
        std::vector<Query> queries;
        std::vector<Candidate> near;
        for (int u = range.begin(); u != range.end(); ++u) {
          if (!triangles.gridded(u)) {  // stretched or not finite: a query of its own
            const Query q = query_of(u);
            triangles.query(q.box, [&](int o) {
              if (o != u) visit(u, q, o, t);
            });
            continue;
          }
          if (!triangles.leads(u)) continue;  // its cell's first triangle takes it
          mates.clear();
          queries.clear();
          BoxGrid::FloatBox all_queries{{INFINITY, INFINITY, INFINITY}, {-INFINITY, -INFINITY, -INFINITY}};
          triangles.for_each_cellmate(u, [&](int m) {
            const Query& q = queries.emplace_back(query_of(m));
            if (q.box.isEmpty()) {
              queries.pop_back();
              return;
            }
            mates.push_back(m);
            for (int k = 0; k < 3; ++k) {
              all_queries.lo[k] = std::min(all_queries.lo[k], q.bounds.lo[k]);
              all_queries.hi[k] = std::max(all_queries.hi[k], q.bounds.hi[k]);
            }
          });
          near.clear();
          triangles.for_each_near(u, [&](int o, const BoxGrid::FloatBox& b) {
            if (b.overlaps(all_queries)) near.push_back({b, o});
          });
          for (std::size_t m = 0; m < mates.size(); ++m) {
            const Query& q = queries[m];
            for (const Candidate& c : near) {
              if (c.id == mates[m]) continue;  // its own triangle: every pair shares a vertex
              if (c.bounds.overlaps(q.bounds) && triangles.box(c.id).intersects(q.box)) visit(mates[m], q, c.id, t);
            }
          }
        }
        return t;
      },
      joined);
  out.vertex_triangle = all.vertex_triangle;
  out.edge_edge = all.edge_edge;
  out.crossings = all.crossings;
  out.max_penetration = out.pairs() > 0 ? r - all.closest : 0.0;
  return out;
}

bool segment_crosses_triangle(const Vector3d& p, const Vector3d& q, const Vector3d& a, const Vector3d& b,
                              const Vector3d& c) {
  return crosses(p, q, a, b, c, (b - a).cross(c - a));
}

}  // namespace atssim::solver
