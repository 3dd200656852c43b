/* The broad phase and the pair lists of contact between simulated surfaces
 * (kernels/contact/self_contact.cl), in the common subset of C, C++ and
 * OpenCL C, so that the kernels and the host (bench/broad_phase, the tests)
 * run the same code: the refit of the implicit BVH of
 * solver/layout/self_contact_layout (level 0: the triangles in leaf order;
 * node j of level l has children 2j, 2j + 1 of level l - 1; nodes[2 g],
 * nodes[2 g + 1] are the box of node g = levels[l] + j), its depth-first walk,
 * and the walk per leaf that fills the lists: per vertex the triangles, per
 * triangle the vertices, per edge the edges, closer than the query radius,
 * incident pairs (a shared vertex) excluded, the ATS_SC_CAPACITY nearest of
 * each. A list is ATS_SC_STRIDE ints: [count,
 * horizon (float bits, sc_list_store), ids of the nearest first].
 *
 * Host code defines ats_float4 (its 16-byte x, y, z, w struct) before the
 * first include; the scalar type is float. Topology arrays are plain ints:
 * tris 4 per triangle ([3] unused), edges 2 per edge, leaves 8 per leaf
 * (owned vertices [0..2], owned edges [4..6], -1: none). */
#ifndef ATS_SELF_CONTACT_BVH_H
#define ATS_SELF_CONTACT_BVH_H

#include "common/ats_math.h"
#include "common/self_contact.h"

#define ATS_SC_CAPACITY 8
#define ATS_SC_STRIDE (ATS_SC_CAPACITY + 2)
#define ATS_SC_STACK 64

#ifdef __OPENCL_VERSION__
#define sc_float_bits(f) as_int(f)
#define sc_bits_float(i) as_float(i)
#else
#include <string.h>
ATS_FN int sc_float_bits(float f) {
  int i;
  memcpy(&i, &f, sizeof i);
  return i;
}
ATS_FN float sc_bits_float(int i) {
  float f;
  memcpy(&f, &i, sizeof f);
  return f;
}
#endif

ATS_FN ats_vec3 sc_v(ats_float4 p) { return ats_v3(p.x, p.y, p.z); }

typedef struct {
  ats_vec3 lo, hi;
} sc_box;

ATS_FN ats_vec3 sc_min3(ats_vec3 a, ats_vec3 b) { return ats_v3(fmin(a.x, b.x), fmin(a.y, b.y), fmin(a.z, b.z)); }
ATS_FN ats_vec3 sc_max3(ats_vec3 a, ats_vec3 b) { return ats_v3(fmax(a.x, b.x), fmax(a.y, b.y), fmax(a.z, b.z)); }

/* The box of points a, b (and c) widened by r on every side. */
ATS_FN sc_box sc_box_widened(sc_box b, float r) {
  b.lo = ats_v3(b.lo.x - r, b.lo.y - r, b.lo.z - r);
  b.hi = ats_v3(b.hi.x + r, b.hi.y + r, b.hi.z + r);
  return b;
}
ATS_FN sc_box sc_box_of_point(ats_vec3 p, float r) {
  sc_box b;
  b.lo = p;
  b.hi = p;
  return sc_box_widened(b, r);
}
ATS_FN sc_box sc_box_of_edge(ats_vec3 a, ats_vec3 b, float r) {
  sc_box out;
  out.lo = sc_min3(a, b);
  out.hi = sc_max3(a, b);
  return sc_box_widened(out, r);
}
ATS_FN sc_box sc_box_of_triangle(ats_vec3 a, ats_vec3 b, ats_vec3 c, float r) {
  sc_box out;
  out.lo = sc_min3(a, sc_min3(b, c));
  out.hi = sc_max3(a, sc_max3(b, c));
  return sc_box_widened(out, r);
}

ATS_FN int sc_boxes_overlap(sc_box a, sc_box b) {
  return !(a.lo.x > b.hi.x || a.lo.y > b.hi.y || a.lo.z > b.hi.z || a.hi.x < b.lo.x || a.hi.y < b.lo.y ||
           a.hi.z < b.lo.z);
}
ATS_FN int sc_box_holds(sc_box b, ats_vec3 p) {
  return !(p.x < b.lo.x || p.y < b.lo.y || p.z < b.lo.z || p.x > b.hi.x || p.y > b.hi.y || p.z > b.hi.z);
}

ATS_FN sc_box sc_node_box(ATS_GLOBAL const ats_float4* nodes, int g) {
  sc_box b;
  b.lo = sc_v(nodes[2 * g]);
  b.hi = sc_v(nodes[2 * g + 1]);
  return b;
}
ATS_FN void sc_store_node(ATS_GLOBAL ats_float4* nodes, int g, sc_box b) {
  nodes[2 * g].x = b.lo.x;
  nodes[2 * g].y = b.lo.y;
  nodes[2 * g].z = b.lo.z;
  nodes[2 * g].w = 0.0f;
  nodes[2 * g + 1].x = b.hi.x;
  nodes[2 * g + 1].y = b.hi.y;
  nodes[2 * g + 1].z = b.hi.z;
  nodes[2 * g + 1].w = 0.0f;
}

/* Leaf t: the box of its triangle. */
ATS_FN void sc_leaf_box(int t, ATS_GLOBAL const ats_float4* x, ATS_GLOBAL const int* tris,
                        ATS_GLOBAL ats_float4* nodes) {
  ATS_GLOBAL const int* f = tris + 4 * t;
  sc_store_node(nodes, t, sc_box_of_triangle(sc_v(x[f[0]]), sc_v(x[f[1]]), sc_v(x[f[2]]), 0.0f));
}

/* Node g from children c and c + 1 (if c + 1 < children) at child_offset. */
ATS_FN void sc_refit_node(ATS_GLOBAL ats_float4* nodes, int g, int child_offset, int c, int children) {
  sc_box b = sc_node_box(nodes, child_offset + c);
  if (c + 1 < children) {
    const sc_box o = sc_node_box(nodes, child_offset + c + 1);
    b.lo = sc_min3(b.lo, o.lo);
    b.hi = sc_max3(b.hi, o.hi);
  }
  sc_store_node(nodes, g, b);
}

/* The levels from `from` to `root`, each after the one below. */
ATS_FN void sc_refit_levels(ATS_GLOBAL ats_float4* nodes, ATS_GLOBAL const int* levels, int from, int root) {
  for (int l = from; l <= root; ++l) {
    const int count = levels[l + 1] - levels[l], children = levels[l] - levels[l - 1];
    for (int j = 0; j < count; ++j) sc_refit_node(nodes, levels[l] + j, levels[l - 1], 2 * j, children);
  }
}

/* Depth-first walk: a child is tested before it is pushed, so the stack
 * holds only nodes whose box overlaps the query. */
typedef struct {
  int level[ATS_SC_STACK];
  int index[ATS_SC_STACK];
  int top;
} sc_walk;

ATS_FN void sc_walk_begin(sc_walk* w, ATS_GLOBAL const ats_float4* nodes, ATS_GLOBAL const int* levels, int root,
                          sc_box q) {
  w->top = 0;
  if (!sc_boxes_overlap(sc_node_box(nodes, levels[root]), q)) return;
  w->level[0] = root;
  w->index[0] = 0;
  w->top = 1;
}

/* The next leaf whose box overlaps q, or -1. */
ATS_FN int sc_walk_next(sc_walk* w, ATS_GLOBAL const ats_float4* nodes, ATS_GLOBAL const int* levels, sc_box q) {
  while (w->top > 0) {
    --w->top;
    const int l = w->level[w->top], j = w->index[w->top];
    if (l == 0) return j;
    const int children = levels[l] - levels[l - 1];
    /* right child pushed first: the left one is walked first */
    for (int c = 1; c >= 0; --c) {
      const int k = 2 * j + c;
      if (k < children && w->top < ATS_SC_STACK && sc_boxes_overlap(sc_node_box(nodes, levels[l - 1] + k), q)) {
        w->level[w->top] = l - 1;
        w->index[w->top] = k;
        ++w->top;
      }
    }
  }
  return -1;
}

/* The ATS_SC_CAPACITY nearest of a query. */
typedef struct {
  int count;
  int id[ATS_SC_CAPACITY];
  float d[ATS_SC_CAPACITY];
} sc_list;

ATS_FN void sc_list_begin(sc_list* l) { l->count = 0; }

ATS_FN void sc_list_insert(sc_list* l, int id, float d) {
  int k;
  if (l->count < ATS_SC_CAPACITY) {
    k = l->count++;
  } else {
    if (!(d < l->d[ATS_SC_CAPACITY - 1])) return;
    k = ATS_SC_CAPACITY - 1;
  }
  while (k > 0 && l->d[k - 1] > d) {
    l->d[k] = l->d[k - 1];
    l->id[k] = l->id[k - 1];
    --k;
  }
  l->d[k] = d;
  l->id[k] = id;
}

/* [1]: the list's horizon, the distance every primitive it does not hold
 * was at least at: the radius, or the farthest kept one when it is full. */
ATS_FN void sc_list_store(const sc_list* l, float radius, ATS_GLOBAL int* out) {
  out[0] = l->count;
  out[1] = sc_float_bits(l->count == ATS_SC_CAPACITY ? l->d[ATS_SC_CAPACITY - 1] : radius);
  for (int k = 0; k < l->count; ++k) out[2 + k] = l->id[k];
}

/* inc: [0, n]: offsets of each particle's incident triangles, [n + 1, 2n + 1]:
 * of its incident edges, [2n + 2, 3n + 2]: of its joined vertices (the other
 * corners of its triangles, each once; sc_joined); then the lists. */
ATS_FN int sc_is_surface(ATS_GLOBAL const int* inc, int i) { return inc[i + 1] > inc[i]; }

/* Whether triangle f (its corners) has corner v. */
ATS_FN int sc_has_corner(ATS_GLOBAL const int* f, int v) { return f[0] == v || f[1] == v || f[2] == v; }

/* The three queries of leaf u: the triangle's own list (per triangle the
 * vertices), the lists of the vertices it owns (per vertex the triangles)
 * and of the edges it owns (per edge the edges), each primitive owned by
 * exactly one leaf (solver/layout/self_contact_layout), so every list has
 * one writer. Its candidates are the leaves whose box overlaps the
 * triangle's box widened by the radius (q), which holds every owned
 * primitive's widened box; each candidate is then tested against each owned
 * primitive's own box, so each list sees the candidates of its own query in
 * leaf order, as a walk of its own would. */
typedef struct {
  int u;
  int f[3];
  int n;                /* the particles (inc's sections) */
  ats_vec3 a, b, c, nu; /* nu: the triangle's (unnormalised) normal */
  sc_box q;
  sc_list tri;
  int vid[3]; /* owned vertices: id (-1: none or not a query), point, widened box */
  ats_vec3 vp[3];
  sc_box vq[3];
  sc_list vl[3];
  int eid[3], e0[3], e1[3]; /* owned edges: id, ends, widened box */
  ats_vec3 ea[3], eb[3];
  int enn[3]; /* the normals of the edge's triangles (sc_edge_in_plane's), how many; -1: more than 2 */
  ats_vec3 en[3][2];
  sc_box eq[3];
  sc_list el[3];
} sc_leaf_query;

ATS_FN void sc_leaf_begin(sc_leaf_query* lq, int u, int n, ATS_GLOBAL const ats_float4* x, ATS_GLOBAL const int* inc,
                          ATS_GLOBAL const int* tris, ATS_GLOBAL const int* edges, ATS_GLOBAL const int* leaves,
                          float radius) {
  ATS_GLOBAL const int* f = tris + 4 * u;
  ATS_GLOBAL const int* own = leaves + 8 * u;
  lq->u = u;
  lq->n = n;
  for (int k = 0; k < 3; ++k) lq->f[k] = f[k];
  lq->a = sc_v(x[f[0]]);
  lq->b = sc_v(x[f[1]]);
  lq->c = sc_v(x[f[2]]);
  lq->q = sc_box_of_triangle(lq->a, lq->b, lq->c, radius);
  lq->nu = ats_plane_normal(lq->a, lq->b, lq->c);
  sc_list_begin(&lq->tri);
  for (int k = 0; k < 3; ++k) {
    int v = own[k];
    sc_list_begin(&lq->vl[k]);
    if (v >= 0 && !sc_is_surface(inc, v)) v = -1;
    lq->vid[k] = v;
    lq->vp[k] = v >= 0 ? sc_v(x[v]) : lq->a;
    lq->vq[k] = sc_box_of_point(lq->vp[k], radius);
  }
  for (int k = 0; k < 3; ++k) {
    const int e = own[4 + k];
    lq->eid[k] = e;
    sc_list_begin(&lq->el[k]);
    lq->e0[k] = e >= 0 ? edges[2 * e] : -1;
    lq->e1[k] = e >= 0 ? edges[2 * e + 1] : -1;
    lq->ea[k] = e >= 0 ? sc_v(x[lq->e0[k]]) : lq->a;
    lq->eb[k] = e >= 0 ? sc_v(x[lq->e1[k]]) : lq->a;
    lq->eq[k] = sc_box_of_edge(lq->ea[k], lq->eb[k], radius);
    lq->enn[k] = 0;
    for (int m = e >= 0 ? inc[lq->e0[k]] : 0; e >= 0 && m < inc[lq->e0[k] + 1]; ++m) {
      ATS_GLOBAL const int* g = tris + 4 * inc[m];
      if (!sc_has_corner(g, lq->e1[k])) continue;
      if (lq->enn[k] == 2) {  // a non-manifold edge: sc_edge_in_plane per candidate
        lq->enn[k] = -1;
        break;
      }
      lq->en[k][lq->enn[k]++] = ats_plane_normal(sc_v(x[g[0]]), sc_v(x[g[1]]), sc_v(x[g[2]]));
    }
  }
}

/* Whether segments (a0, a1) and (b0, b1) are certainly at least `radius`
 * apart, by one separating axis: the offset between their midpoints less
 * its part along the first segment (u, scaled by |a1 - a0|^2 to need no
 * division), on which the first projects to a point. The separation of the
 * projections over |u| bounds the distance from below; 1e-3 of margin, far
 * above the rounding of both it and the distance (all relative to a0), so
 * where it says apart ats_edge_edge's d is >= radius too and the lists are
 * those the exact test alone makes. Cloth's neighbouring edges (a diagonal
 * beside a parallel one) fail the boxes' test and pass this one. */
ATS_FN int sc_segments_apart(ats_vec3 a0, ats_vec3 a1, ats_vec3 b0, ats_vec3 b1, float radius) {
  const ats_vec3 d = ats_sub(a1, a0), p = ats_sub(b0, a0), q = ats_sub(b1, a0);
  const ats_vec3 m = ats_scale(ats_sub(ats_add(p, q), d), 0.5f);
  const float dd = ats_dot(d, d);
  const ats_vec3 u = ats_sub(ats_scale(m, dd), ats_scale(d, ats_dot(m, d)));
  const float ua = ats_dot(u, d), s0 = ats_dot(u, p), s1 = ats_dot(u, q);
  const float sep = fmax(fmin(s0, s1) - fmax(ua, 0.0f), fmin(ua, 0.0f) - fmax(s0, s1));
  return sep > 0.0f && sep * sep > 1.001f * radius * radius * ats_dot(u, u);
}

/* Sheet neighbours (common/self_contact.h ats_pair_in_plane): whether
 * vertex v and a corner of (a, b, c) are corners of one triangle: a, b or
 * c is v (of a surface vertex) or among v's joined vertices (inc, n
 * particles). */
ATS_FN int sc_joined(ATS_GLOBAL const int* inc, int n, int v, int a, int b, int c) {
  if (a == v || b == v || c == v) return inc[v + 1] > inc[v];
  for (int k = inc[2 * n + 2 + v]; k < inc[2 * n + 3 + v]; ++k) {
    const int w = inc[k];
    if (w == a || w == b || w == c) return 1;
  }
  return 0;
}

/* Whether D lies in the plane of every triangle of edge (e0, e1). */
ATS_FN int sc_edge_in_plane(ATS_GLOBAL const ats_float4* x, ATS_GLOBAL const int* inc, ATS_GLOBAL const int* tris,
                            int e0, int e1, ats_vec3 diff) {
  for (int k = inc[e0]; k < inc[e0 + 1]; ++k) {
    ATS_GLOBAL const int* f = tris + 4 * inc[k];
    if (sc_has_corner(f, e1) && !ats_pair_in_plane(diff, sc_v(x[f[0]]), sc_v(x[f[1]]), sc_v(x[f[2]]))) return 0;
  }
  return 1;
}

/* Vertex v and triangle f (corners a, b, c) at offset D: sheet neighbours. */
ATS_FN int sc_sheet_vertex_triangle(ATS_GLOBAL const int* inc, int n, int v, const int* f, ats_vec3 diff, ats_vec3 a,
                                    ats_vec3 b, ats_vec3 c) {
  return ats_pair_in_plane(diff, a, b, c) && sc_joined(inc, n, v, f[0], f[1], f[2]);
}

/* u's edge k and edge (o0, o1) at offset D: sheet neighbours when the
 * edges are joined (an end of one and an end of the other corners of one
 * triangle, sc_joined) and D lies in the plane of every triangle of both
 * edges. The three tests, the cheapest first: D in the plane of edge k's
 * triangles (a dot product with each normal gathered in sc_leaf_begin; a
 * non-manifold edge's are read in sc_edge_in_plane), then the joined scan,
 * then D in the plane of the candidate's triangles (read from memory).
 * Edges of two layers pressed together, most pairs of a crowd, fail the
 * first. */
ATS_FN int sc_leaf_sheet_edge(const sc_leaf_query* lq, int k, ATS_GLOBAL const ats_float4* x, ATS_GLOBAL const int* inc,
                              ATS_GLOBAL const int* tris, int o0, int o1, ats_vec3 diff) {
  for (int m = 0; m < lq->enn[k]; ++m)
    if (!ats_in_plane_of(diff, lq->en[k][m])) return 0;
  if (!sc_joined(inc, lq->n, lq->e0[k], o0, o1, o1) && !sc_joined(inc, lq->n, lq->e1[k], o0, o1, o1)) return 0;
  if (lq->enn[k] < 0 && !sc_edge_in_plane(x, inc, tris, lq->e0[k], lq->e1[k], diff)) return 0;
  return sc_edge_in_plane(x, inc, tris, o0, o1, diff);
}

/* Candidate leaf o (its box overlaps q). */
ATS_FN void sc_leaf_candidate(sc_leaf_query* lq, int o, ATS_GLOBAL const ats_float4* x, ATS_GLOBAL const int* inc,
                              ATS_GLOBAL const int* tris, ATS_GLOBAL const int* edges, ATS_GLOBAL const int* leaves,
                              ATS_GLOBAL const ats_float4* nodes, float radius) {
  ATS_GLOBAL const int* g = tris + 4 * o;
  ATS_GLOBAL const int* theirs = leaves + 8 * o;
  const sc_box ob = sc_node_box(nodes, o);
  /* per triangle the vertices: the vertices leaf o owns, near triangle u */
  for (int k = 0; k < 3; ++k) {
    const int v = theirs[k];
    if (v < 0 || v == lq->f[0] || v == lq->f[1] || v == lq->f[2]) continue;
    const ats_vec3 p = sc_v(x[v]);
    if (!sc_box_holds(lq->q, p)) continue;
    const ats_pair_geometry pg = ats_point_triangle(p, lq->a, lq->b, lq->c);
    if (pg.d < radius && !(ats_in_plane_of(pg.diff, lq->nu) && sc_joined(inc, lq->n, v, lq->f[0], lq->f[1], lq->f[2])))
      sc_list_insert(&lq->tri, v, pg.d);
  }
  /* per vertex the triangles: triangle o, near each vertex u owns (its
   * corners read once for all of them) */
  int near = 0;
  for (int k = 0; k < 3; ++k) {
    const int v = lq->vid[k];
    if (v >= 0 && g[0] != v && g[1] != v && g[2] != v && sc_boxes_overlap(ob, lq->vq[k])) near |= 1 << k;
  }
  if (near) {
    const ats_vec3 ga = sc_v(x[g[0]]), gb = sc_v(x[g[1]]), gc = sc_v(x[g[2]]);
    const int gf[3] = {g[0], g[1], g[2]};
    for (int k = 0; k < 3; ++k) {
      if (!(near & (1 << k))) continue;
      const ats_pair_geometry pg = ats_point_triangle(lq->vp[k], ga, gb, gc);
      if (pg.d < radius && !sc_sheet_vertex_triangle(inc, lq->n, lq->vid[k], gf, pg.diff, ga, gb, gc))
        sc_list_insert(&lq->vl[k], o, pg.d);
    }
  }
  /* per edge the edges: the edges leaf o owns, near each edge u owns (each
   * candidate read once for all of them; a list sees its candidates in the
   * same order either way) */
  near = 0;
  for (int k = 0; k < 3; ++k)
    if (lq->eid[k] >= 0 && sc_boxes_overlap(ob, lq->eq[k])) near |= 1 << k;
  for (int m = 4; near && m < 7; ++m) {
    const int h = theirs[m];
    if (h < 0) continue;
    const int o0 = edges[2 * h], o1 = edges[2 * h + 1];
    const ats_vec3 p0 = sc_v(x[o0]), p1 = sc_v(x[o1]);
    const sc_box hb = sc_box_of_edge(p0, p1, 0.0f);
    for (int k = 0; k < 3; ++k) {
      if (!(near & (1 << k)) || h == lq->eid[k]) continue;
      if (o0 == lq->e0[k] || o0 == lq->e1[k] || o1 == lq->e0[k] || o1 == lq->e1[k] || !sc_boxes_overlap(lq->eq[k], hb))
        continue;
      if (sc_segments_apart(lq->ea[k], lq->eb[k], p0, p1, radius)) continue;
      const ats_pair_geometry pg = ats_edge_edge(lq->ea[k], lq->eb[k], p0, p1);
      if (pg.d < radius && !sc_leaf_sheet_edge(lq, k, x, inc, tris, o0, o1, pg.diff))
        sc_list_insert(&lq->el[k], h, pg.d);
    }
  }
}

ATS_FN void sc_leaf_end(const sc_leaf_query* lq, float radius, ATS_GLOBAL const int* leaves, ATS_GLOBAL int* vt,
                        ATS_GLOBAL int* tv, ATS_GLOBAL int* ee) {
  ATS_GLOBAL const int* own = leaves + 8 * lq->u;
  sc_list_store(&lq->tri, radius, tv + lq->u * ATS_SC_STRIDE);
  for (int k = 0; k < 3; ++k) {
    if (own[k] >= 0) sc_list_store(&lq->vl[k], radius, vt + own[k] * ATS_SC_STRIDE);
    if (lq->eid[k] >= 0) sc_list_store(&lq->el[k], radius, ee + lq->eid[k] * ATS_SC_STRIDE);
  }
}

/* Leaf u's lists by a walk of its own. */
ATS_FN void sc_query_leaf(int u, int n, ATS_GLOBAL const ats_float4* x, ATS_GLOBAL const int* inc,
                          ATS_GLOBAL const int* tris, ATS_GLOBAL const int* edges, ATS_GLOBAL const int* leaves,
                          ATS_GLOBAL const ats_float4* nodes, ATS_GLOBAL const int* levels, int root, float radius,
                          ATS_GLOBAL int* vt, ATS_GLOBAL int* tv, ATS_GLOBAL int* ee) {
  sc_leaf_query lq;
  sc_leaf_begin(&lq, u, n, x, inc, tris, edges, leaves, radius);
  sc_walk w;
  sc_walk_begin(&w, nodes, levels, root, lq.q);
  int o;
  while ((o = sc_walk_next(&w, nodes, levels, lq.q)) >= 0)
    sc_leaf_candidate(&lq, o, x, inc, tris, edges, leaves, nodes, radius);
  sc_leaf_end(&lq, radius, leaves, vt, tv, ee);
}

/* The lists of the ATS_SC_GROUP leaves of group g (leaves [g G, g G + G)):
 * one walk with their joint box widened by the radius gathers the candidate
 * leaves (in leaf order), and each leaf takes those whose box overlaps its
 * own query box, which are the leaves its own walk would meet, in the same
 * order: the same lists for an eighth of the walks. When the candidates
 * outgrow ATS_SC_GROUP_CANDIDATES, each leaf walks on its own. */
#define ATS_SC_GROUP 8
#define ATS_SC_GROUP_CANDIDATES 192
ATS_FN void sc_query_group(int g, int leaf_count, int n, ATS_GLOBAL const ats_float4* x, ATS_GLOBAL const int* inc,
                           ATS_GLOBAL const int* tris, ATS_GLOBAL const int* edges, ATS_GLOBAL const int* leaves,
                           ATS_GLOBAL const ats_float4* nodes, ATS_GLOBAL const int* levels, int root, float radius,
                           ATS_GLOBAL int* vt, ATS_GLOBAL int* tv, ATS_GLOBAL int* ee) {
  const int first = g * ATS_SC_GROUP;
  const int end = first + ATS_SC_GROUP < leaf_count ? first + ATS_SC_GROUP : leaf_count;
  sc_box q = sc_node_box(nodes, first);
  for (int u = first + 1; u < end; ++u) {
    const sc_box b = sc_node_box(nodes, u);
    q.lo = sc_min3(q.lo, b.lo);
    q.hi = sc_max3(q.hi, b.hi);
  }
  q = sc_box_widened(q, radius);
  int cand[ATS_SC_GROUP_CANDIDATES];
  int count = 0, overflow = 0;
  sc_walk w;
  sc_walk_begin(&w, nodes, levels, root, q);
  int o;
  while (!overflow && (o = sc_walk_next(&w, nodes, levels, q)) >= 0) {
    if (count < ATS_SC_GROUP_CANDIDATES)
      cand[count++] = o;
    else
      overflow = 1;
  }
  for (int u = first; u < end; ++u) {
    if (overflow) {
      sc_query_leaf(u, n, x, inc, tris, edges, leaves, nodes, levels, root, radius, vt, tv, ee);
      continue;
    }
    sc_leaf_query lq;
    sc_leaf_begin(&lq, u, n, x, inc, tris, edges, leaves, radius);
    for (int k = 0; k < count; ++k)
      if (sc_boxes_overlap(sc_node_box(nodes, cand[k]), lq.q))
        sc_leaf_candidate(&lq, cand[k], x, inc, tris, edges, leaves, nodes, radius);
    sc_leaf_end(&lq, radius, leaves, vt, tv, ee);
  }
}

#endif
