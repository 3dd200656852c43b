#pragma once
// The device's broad phase on the host: the kernels' own code
// (kernels/common/self_contact_bvh.h, compiled here) refits the implicit BVH
// of solver/layout/self_contact_layout (built once) from the leaf boxes up
// and walks it depth-first; per vertex the triangles, per triangle the
// vertices its leaves own, per edge the edges its leaves own. Unlike the
// kernels' queries (bvh_kernel_lists below), every pair is kept, so two
// broad phases can be compared pair for pair.
#include <vector>

#include "broad_phase/surface_pairs.hpp"
#include "solver/layout/sim_layout.hpp"

namespace atssim::bench {

using solver::Float4;

// The kernels' positions (float4, w unused here) of the bench's points.
inline std::vector<Float4> float4_positions(const std::vector<ats_vec3>& x) {
  std::vector<Float4> out(x.size());
  for (std::size_t i = 0; i < x.size(); ++i) out[i] = {x[i].x, x[i].y, x[i].z, 1.0f};
  return out;
}

// nodes: two float4 per node (sc_leaf_boxes).
inline void bvh_leaf_boxes(const SelfContactLayout& s, const std::vector<Float4>& x, std::vector<Float4>& nodes,
                           int begin, int end) {
  for (int t = begin; t < end; ++t) sc_leaf_box(t, x.data(), s.tris[0].data(), nodes.data());
}

// Nodes [begin, end) of level l from their children (sc_refit_level).
inline void bvh_refit_level(const SelfContactLayout& s, std::vector<Float4>& nodes, int l, int begin, int end) {
  for (int j = begin; j < end; ++j)
    sc_refit_node(nodes.data(), s.levels[l] + j, s.levels[l - 1], 2 * j, s.levels[l] - s.levels[l - 1]);
}

inline int bvh_level_size(const SelfContactLayout& s, int l) { return s.levels[l + 1] - s.levels[l]; }

inline sc_box sc_box_of(const Box& b) {
  sc_box out;
  out.lo = ats_v3(b.lo[0], b.lo[1], b.lo[2]);
  out.hi = ats_v3(b.hi[0], b.hi[1], b.hi[2]);
  return out;
}

// Calls leaf(j) for every leaf whose box overlaps q, in the kernels' order (sc_walk_next).
template <typename Leaf>
void bvh_walk(const SelfContactLayout& s, const std::vector<Float4>& nodes, const Box& box, Leaf&& leaf) {
  const sc_box q = sc_box_of(box);
  sc_walk w;
  sc_walk_begin(&w, nodes.data(), s.levels.data(), s.root(), q);
  for (int j; (j = sc_walk_next(&w, nodes.data(), s.levels.data(), q)) >= 0;) leaf(j);
}

inline void bvh_query_vertices(const SelfContactLayout& s, const std::vector<ats_vec3>& x,
                               const std::vector<Float4>& nodes, float r, int begin, int end, PairLists& out) {
  for (int i = begin; i < end; ++i) {
    if (!is_surface(s, i)) continue;
    bvh_walk(s, nodes, point_box(x[i], r), [&](int t) { test_vertex_triangle(s, x, i, t, r, out, true); });
  }
}

inline void bvh_query_triangles(const SelfContactLayout& s, const std::vector<ats_vec3>& x,
                                const std::vector<Float4>& nodes, float r, int begin, int end, PairLists& out) {
  for (int t = begin; t < end; ++t) {
    const auto& f = s.tris[t];
    bvh_walk(s, nodes, triangle_box(x[f[0]], x[f[1]], x[f[2]], r), [&](int u) {
      for (int k = 0; k < 3; ++k)
        if (const int v = s.leaves[u][k]; v >= 0) test_vertex_triangle(s, x, v, t, r, out, false);
    });
  }
}

inline void bvh_query_edges(const SelfContactLayout& s, const std::vector<ats_vec3>& x,
                            const std::vector<Float4>& nodes, float r, int begin, int end, PairLists& out) {
  for (int e = begin; e < end; ++e) {
    bvh_walk(s, nodes, edge_box(x[s.edges[e][0]], x[s.edges[e][1]], r), [&](int u) {
      for (int k = 4; k < 7; ++k)
        if (const int f = s.leaves[u][k]; f >= 0) test_edge_edge(s, x, e, f, r, out);
    });
  }
}

// The kernels' lists, ATS_SC_STRIDE ints per primitive.
struct KernelLists {
  std::vector<int> vt, tv, ee;
  void resize(const SelfContactLayout& s, std::size_t n) {
    vt.resize(n * ATS_SC_STRIDE);
    tv.resize(s.tris.size() * ATS_SC_STRIDE);
    ee.resize(s.edges.size() * ATS_SC_STRIDE);
  }
};

// The kernels' detection as the device runs it (sc_query_groups): the
// three queries of groups [begin, end) of ATS_SC_GROUP leaves, one walk each.
inline int bvh_group_count(const SelfContactLayout& s) {
  return (static_cast<int>(s.tris.size()) + ATS_SC_GROUP - 1) / ATS_SC_GROUP;
}
inline void bvh_group_lists(const SelfContactLayout& s, const std::vector<Float4>& x, const std::vector<Float4>& nodes,
                            float r, int begin, int end, KernelLists& out) {
  for (int g = begin; g < end; ++g)
    sc_query_group(g, static_cast<int>(s.tris.size()), static_cast<int>(x.size()), x.data(), s.incidence.data(),
                   s.tris[0].data(), s.edges[0].data(), s.leaves[0].data(), nodes.data(), s.levels.data(), s.root(), r,
                   out.vt.data(), out.tv.data(), out.ee.data());
}

// One substep's detection, single-threaded: refit, then the three queries.
inline void bvh_refit(const SelfContactLayout& s, const std::vector<ats_vec3>& x, std::vector<Float4>& nodes) {
  nodes.resize(2 * std::size_t(s.node_count()));
  const std::vector<Float4> xf = float4_positions(x);
  bvh_leaf_boxes(s, xf, nodes, 0, static_cast<int>(s.tris.size()));
  for (int l = 1; l <= s.root(); ++l) bvh_refit_level(s, nodes, l, 0, bvh_level_size(s, l));
}

inline void bvh_query(const SelfContactLayout& s, const std::vector<ats_vec3>& x, const std::vector<Float4>& nodes,
                      float r, PairLists& out) {
  bvh_query_vertices(s, x, nodes, r, 0, static_cast<int>(x.size()), out);
  bvh_query_triangles(s, x, nodes, r, 0, static_cast<int>(s.tris.size()), out);
  bvh_query_edges(s, x, nodes, r, 0, static_cast<int>(s.edges.size()), out);
}

}  // namespace atssim::bench
