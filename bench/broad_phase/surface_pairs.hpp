#pragma once
// What the self-contact queries find (kernels/contact/self_contact.cl
// sc_query_groups), on the host in float through the
// kernels' own narrow phase (common/self_contact.h): every vertex-triangle
// and edge-edge pair closer than the query radius, incident pairs and sheet
// neighbours excluded (common/self_contact_bvh.h sc_sheet_*).
// Unlike the kernels, which keep the 8 nearest per primitive, all pairs are
// kept, so two broad phases can be compared pair for pair.
#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <vector>

#include "solver/layout/self_contact_layout.hpp"
#include "solver/layout/sim_layout.hpp"

#define ats_float4 ::atssim::solver::Float4
#include "common/self_contact_bvh.h"

namespace atssim::bench {

using solver::SelfContactLayout;

// An axis-aligned box in float, as the kernels' float4 pairs.
struct Box {
  float lo[3], hi[3];
};

inline bool overlap(const Box& a, const Box& b) {
  return !(a.lo[0] > b.hi[0] || a.lo[1] > b.hi[1] || a.lo[2] > b.hi[2] || a.hi[0] < b.lo[0] || a.hi[1] < b.lo[1] ||
           a.hi[2] < b.lo[2]);
}

inline Box point_box(const ats_vec3& p, float r) { return {{p.x - r, p.y - r, p.z - r}, {p.x + r, p.y + r, p.z + r}}; }

inline Box triangle_box(const ats_vec3& a, const ats_vec3& b, const ats_vec3& c, float r) {
  return {{std::fmin(a.x, std::fmin(b.x, c.x)) - r, std::fmin(a.y, std::fmin(b.y, c.y)) - r,
           std::fmin(a.z, std::fmin(b.z, c.z)) - r},
          {std::fmax(a.x, std::fmax(b.x, c.x)) + r, std::fmax(a.y, std::fmax(b.y, c.y)) + r,
           std::fmax(a.z, std::fmax(b.z, c.z)) + r}};
}

inline Box edge_box(const ats_vec3& a, const ats_vec3& b, float r) {
  return {{std::fmin(a.x, b.x) - r, std::fmin(a.y, b.y) - r, std::fmin(a.z, b.z) - r},
          {std::fmax(a.x, b.x) + r, std::fmax(a.y, b.y) + r, std::fmax(a.z, b.z) + r}};
}

// The pairs one query pass found, in the layout's ids (triangles in leaf
// order, the layout's edges), and how many narrow-phase tests it ran.
struct PairLists {
  std::vector<std::array<int, 2>> vt;  // (vertex, triangle): per vertex the triangles
  std::vector<std::array<int, 2>> tv;  // (triangle, vertex): per triangle the vertices
  std::vector<std::array<int, 2>> ee;  // (edge, edge): per edge the edges, each pair both ways
  std::int64_t tested = 0;
  void clear() {
    vt.clear();
    tv.clear();
    ee.clear();
    tested = 0;
  }
  std::size_t found() const { return vt.size() + tv.size() + ee.size(); }
  void append(const PairLists& o) {
    vt.insert(vt.end(), o.vt.begin(), o.vt.end());
    tv.insert(tv.end(), o.tv.begin(), o.tv.end());
    ee.insert(ee.end(), o.ee.begin(), o.ee.end());
    tested += o.tested;
  }
  void sort() {
    std::sort(vt.begin(), vt.end());
    std::sort(tv.begin(), tv.end());
    std::sort(ee.begin(), ee.end());
  }
};

// Positions in float, as the kernels read them.
inline std::vector<ats_vec3> float_positions(const std::vector<Eigen::Vector3d>& x) {
  std::vector<ats_vec3> out;
  out.reserve(x.size());
  for (const auto& p : x) out.push_back(ats_v3(float(p.x()), float(p.y()), float(p.z())));
  return out;
}

// sc_is_surface: a particle with incident triangles.
inline bool is_surface(const SelfContactLayout& s, int i) { return s.incidence[i + 1] > s.incidence[i]; }

// The narrow phase of one candidate, with the kernels' exclusion of incident
// pairs and sheet neighbours; records the pair when it is closer than r.
inline void test_vertex_triangle(const SelfContactLayout& s, const std::vector<ats_vec3>& x, int v, int t, float r,
                                 PairLists& out, bool per_vertex) {
  const auto& f = s.tris[t];
  if (v == f[0] || v == f[1] || v == f[2]) return;
  ++out.tested;
  const ats_pair_geometry g = ats_point_triangle(x[v], x[f[0]], x[f[1]], x[f[2]]);
  if (g.d < r &&
      !sc_sheet_vertex_triangle(s.incidence.data(), int(x.size()), v, f.data(), g.diff, x[f[0]], x[f[1]], x[f[2]]))
    (per_vertex ? out.vt : out.tv).push_back(per_vertex ? std::array{v, t} : std::array{t, v});
}

// sc_edge_in_plane on the bench's positions (ats_vec3, not the kernels' float4).
inline bool edge_in_plane(const SelfContactLayout& s, const std::vector<ats_vec3>& x, int e0, int e1, ats_vec3 diff) {
  for (int k = s.incidence[e0]; k < s.incidence[e0 + 1]; ++k) {
    const auto& f = s.tris[s.incidence[k]];
    if ((f[0] == e1 || f[1] == e1 || f[2] == e1) && !ats_pair_in_plane(diff, x[f[0]], x[f[1]], x[f[2]])) return false;
  }
  return true;
}

inline void test_edge_edge(const SelfContactLayout& s, const std::vector<ats_vec3>& x, int e, int f, float r,
                           PairLists& out) {
  if (f == e) return;
  const auto& a = s.edges[e];
  const auto& b = s.edges[f];
  if (b[0] == a[0] || b[0] == a[1] || b[1] == a[0] || b[1] == a[1]) return;
  ++out.tested;
  const ats_pair_geometry g = ats_edge_edge(x[a[0]], x[a[1]], x[b[0]], x[b[1]]);
  if (!(g.d < r)) return;
  const int* inc = s.incidence.data();
  const int n = int(x.size());
  const bool sheet = (sc_joined(inc, n, a[0], b[0], b[1], b[1]) || sc_joined(inc, n, a[1], b[0], b[1], b[1])) &&
                     edge_in_plane(s, x, a[0], a[1], g.diff) && edge_in_plane(s, x, b[0], b[1], g.diff);
  if (!sheet) out.ee.push_back({e, f});
}

// Every pair tested (a box 1 % wider than r skips the far ones; a pair
// closer than r always passes it), for vertices / triangles / edges in
// [begin, end) of each kind: the reference the broad phases must equal.
inline void brute_force_pairs(const SelfContactLayout& s, const std::vector<ats_vec3>& x, float r, int begin, int end,
                              PairLists& out) {
  const float wide = 1.01f * r;
  const int n = static_cast<int>(x.size()), tris = static_cast<int>(s.tris.size());
  const int edges = static_cast<int>(s.edges.size());
  std::vector<Box> tbox(tris), ebox(edges);
  for (int t = 0; t < tris; ++t) tbox[t] = triangle_box(x[s.tris[t][0]], x[s.tris[t][1]], x[s.tris[t][2]], wide);
  for (int e = 0; e < edges; ++e) ebox[e] = edge_box(x[s.edges[e][0]], x[s.edges[e][1]], 0.0f);
  for (int v = begin; v < std::min(end, n); ++v) {
    if (!is_surface(s, v)) continue;
    const Box q = point_box(x[v], 0.0f);
    for (int t = 0; t < tris; ++t) {
      if (!overlap(q, tbox[t])) continue;
      test_vertex_triangle(s, x, v, t, r, out, true);
      test_vertex_triangle(s, x, v, t, r, out, false);
    }
  }
  for (int e = begin; e < std::min(end, edges); ++e) {
    const Box q = edge_box(x[s.edges[e][0]], x[s.edges[e][1]], wide);
    for (int f = 0; f < edges; ++f)
      if (overlap(q, ebox[f])) test_edge_edge(s, x, e, f, r, out);
  }
}

// Sorted pair sets equal, and the per-triangle lists the transpose of the
// per-vertex ones (both queries find every vertex-triangle pair).
inline bool same_pairs(const PairLists& a, const PairLists& b) { return a.vt == b.vt && a.tv == b.tv && a.ee == b.ee; }

inline bool transposes_agree(const PairLists& sorted) {
  std::vector<std::array<int, 2>> t;
  t.reserve(sorted.tv.size());
  for (const auto& p : sorted.tv) t.push_back({p[1], p[0]});
  std::sort(t.begin(), t.end());
  return t == sorted.vt;
}

}  // namespace atssim::bench
