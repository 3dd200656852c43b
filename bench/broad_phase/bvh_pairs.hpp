#pragma once
// The device's broad phase on the host, step for step: the implicit BVH of
// solver/layout/self_contact_layout (built once) refitted from the leaf
// boxes up (sc_leaf_boxes, sc_refit_level, sc_refit_top) and walked
// depth-first with the kernels' 64-entry stack (sc_walk_next); per vertex
// the triangles, per triangle the vertices its leaves own, per edge the
// edges its leaves own (kernels/contact/self_contact.cl).
#include <vector>

#include "broad_phase/surface_pairs.hpp"

namespace atssim::bench {

// nodes[g]: the box of node g = levels[l] + j (level 0: the leaves).
inline void bvh_leaf_boxes(const SelfContactLayout& s, const std::vector<ats_vec3>& x, std::vector<Box>& nodes,
                           int begin, int end) {
  for (int t = begin; t < end; ++t) nodes[t] = triangle_box(x[s.tris[t][0]], x[s.tris[t][1]], x[s.tris[t][2]], 0.0f);
}

// Nodes [begin, end) of level l from their children (sc_union).
inline void bvh_refit_level(const SelfContactLayout& s, std::vector<Box>& nodes, int l, int begin, int end) {
  const int offset = s.levels[l], child_offset = s.levels[l - 1], children = s.levels[l] - s.levels[l - 1];
  for (int j = begin; j < end; ++j) {
    Box b = nodes[child_offset + 2 * j];
    if (2 * j + 1 < children) {
      const Box& o = nodes[child_offset + 2 * j + 1];
      for (int k = 0; k < 3; ++k) {
        b.lo[k] = std::fmin(b.lo[k], o.lo[k]);
        b.hi[k] = std::fmax(b.hi[k], o.hi[k]);
      }
    }
    nodes[offset + j] = b;
  }
}

inline int bvh_level_size(const SelfContactLayout& s, int l) { return s.levels[l + 1] - s.levels[l]; }

// Calls leaf(j) for every leaf whose box overlaps q, in the kernels' order.
template <typename Leaf>
void bvh_walk(const SelfContactLayout& s, const std::vector<Box>& nodes, const Box& q, Leaf&& leaf) {
  constexpr int kStack = 64;  // ATS_SC_STACK
  int level[kStack], index[kStack];
  int top = 1;
  level[0] = s.root();
  index[0] = 0;
  while (top > 0) {
    --top;
    const int l = level[top], j = index[top];
    if (!overlap(nodes[s.levels[l] + j], q)) continue;
    if (l == 0) {
      leaf(j);
      continue;
    }
    const int children = s.levels[l] - s.levels[l - 1];
    if (2 * j + 1 < children && top < kStack) {
      level[top] = l - 1;
      index[top++] = 2 * j + 1;
    }
    if (top < kStack) {
      level[top] = l - 1;
      index[top++] = 2 * j;
    }
  }
}

inline void bvh_query_vertices(const SelfContactLayout& s, const std::vector<ats_vec3>& x,
                               const std::vector<Box>& nodes, float r, int begin, int end, PairLists& out) {
  for (int i = begin; i < end; ++i) {
    if (!is_surface(s, i)) continue;
    bvh_walk(s, nodes, point_box(x[i], r), [&](int t) { test_vertex_triangle(s, x, i, t, r, out, true); });
  }
}

inline void bvh_query_triangles(const SelfContactLayout& s, const std::vector<ats_vec3>& x,
                                const std::vector<Box>& nodes, float r, int begin, int end, PairLists& out) {
  for (int t = begin; t < end; ++t) {
    const auto& f = s.tris[t];
    bvh_walk(s, nodes, triangle_box(x[f[0]], x[f[1]], x[f[2]], r), [&](int u) {
      for (int k = 0; k < 3; ++k)
        if (const int v = s.leaves[u][k]; v >= 0) test_vertex_triangle(s, x, v, t, r, out, false);
    });
  }
}

inline void bvh_query_edges(const SelfContactLayout& s, const std::vector<ats_vec3>& x, const std::vector<Box>& nodes,
                            float r, int begin, int end, PairLists& out) {
  for (int e = begin; e < end; ++e) {
    bvh_walk(s, nodes, edge_box(x[s.edges[e][0]], x[s.edges[e][1]], r), [&](int u) {
      for (int k = 4; k < 7; ++k)
        if (const int f = s.leaves[u][k]; f >= 0) test_edge_edge(s, x, e, f, r, out);
    });
  }
}

// One substep's detection, single-threaded: refit, then the three queries.
inline void bvh_refit(const SelfContactLayout& s, const std::vector<ats_vec3>& x, std::vector<Box>& nodes) {
  nodes.resize(s.node_count());
  bvh_leaf_boxes(s, x, nodes, 0, static_cast<int>(s.tris.size()));
  for (int l = 1; l <= s.root(); ++l) bvh_refit_level(s, nodes, l, 0, bvh_level_size(s, l));
}

inline void bvh_query(const SelfContactLayout& s, const std::vector<ats_vec3>& x, const std::vector<Box>& nodes,
                      float r, PairLists& out) {
  bvh_query_vertices(s, x, nodes, r, 0, static_cast<int>(x.size()), out);
  bvh_query_triangles(s, x, nodes, r, 0, static_cast<int>(s.tris.size()), out);
  bvh_query_edges(s, x, nodes, r, 0, static_cast<int>(s.edges.size()), out);
}

}  // namespace atssim::bench
