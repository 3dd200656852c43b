/* The broad phase and the pair lists of contact between simulated surfaces
 * (kernels/contact/self_contact.cl), in the common subset of C, C++ and
 * OpenCL C, so that the kernels and the host (bench/broad_phase, the tests)
 * run the same code: the refit of the implicit BVH of
 * solver/layout/self_contact_layout (level 0: the triangles in leaf order;
 * node j of level l has children 2j, 2j + 1 of level l - 1; nodes[2 g],
 * nodes[2 g + 1] are the box of node g = levels[l] + j), its depth-first walk,
 * and the three queries that fill the lists: per vertex the triangles, per
 * triangle the vertices its leaves own, per edge the edges its leaves own,
 * closer than the query radius, incident pairs excluded, the
 * ATS_SC_CAPACITY nearest of each. A list is ATS_SC_STRIDE ints: [count,
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
 * of its incident edges; then the lists. */
ATS_FN int sc_is_surface(ATS_GLOBAL const int* inc, int i) { return inc[i + 1] > inc[i]; }

/* Per vertex i the triangles within radius, into vt + i * ATS_SC_STRIDE. */
ATS_FN void sc_query_vertex(int i, ATS_GLOBAL const ats_float4* x, ATS_GLOBAL const int* inc,
                            ATS_GLOBAL const int* tris, ATS_GLOBAL const ats_float4* nodes,
                            ATS_GLOBAL const int* levels, int root, float radius, ATS_GLOBAL int* vt) {
  sc_list l;
  sc_list_begin(&l);
  if (sc_is_surface(inc, i)) {
    const ats_vec3 p = sc_v(x[i]);
    const sc_box q = sc_box_of_point(p, radius);
    sc_walk w;
    sc_walk_begin(&w, nodes, levels, root, q);
    int t;
    while ((t = sc_walk_next(&w, nodes, levels, q)) >= 0) {
      ATS_GLOBAL const int* f = tris + 4 * t;
      if (f[0] == i || f[1] == i || f[2] == i) continue;
      const ats_pair_geometry g = ats_point_triangle(p, sc_v(x[f[0]]), sc_v(x[f[1]]), sc_v(x[f[2]]));
      if (g.d < radius) sc_list_insert(&l, t, g.d);
    }
  }
  sc_list_store(&l, radius, vt + i * ATS_SC_STRIDE);
}

/* Per triangle t the vertices within radius, into tv + t * ATS_SC_STRIDE. A
 * vertex outside the triangle's widened box cannot be within radius: it is
 * skipped before the narrow phase. */
ATS_FN void sc_query_triangle(int t, ATS_GLOBAL const ats_float4* x, ATS_GLOBAL const int* tris,
                              ATS_GLOBAL const int* leaves, ATS_GLOBAL const ats_float4* nodes,
                              ATS_GLOBAL const int* levels, int root, float radius, ATS_GLOBAL int* tv) {
  sc_list l;
  sc_list_begin(&l);
  ATS_GLOBAL const int* f = tris + 4 * t;
  const ats_vec3 a = sc_v(x[f[0]]), b = sc_v(x[f[1]]), c = sc_v(x[f[2]]);
  const sc_box q = sc_box_of_triangle(a, b, c, radius);
  sc_walk w;
  sc_walk_begin(&w, nodes, levels, root, q);
  int u;
  while ((u = sc_walk_next(&w, nodes, levels, q)) >= 0) {
    for (int k = 0; k < 3; ++k) {
      const int v = leaves[8 * u + k];
      if (v < 0 || v == f[0] || v == f[1] || v == f[2]) continue;
      const ats_vec3 p = sc_v(x[v]);
      if (!sc_box_holds(q, p)) continue;
      const ats_pair_geometry g = ats_point_triangle(p, a, b, c);
      if (g.d < radius) sc_list_insert(&l, v, g.d);
    }
  }
  sc_list_store(&l, radius, tv + t * ATS_SC_STRIDE);
}

/* Per edge e the edges within radius, into ee + e * ATS_SC_STRIDE. An edge
 * whose box misses e's widened box cannot be within radius: skipped before
 * the narrow phase. */
ATS_FN void sc_query_edge(int e, ATS_GLOBAL const ats_float4* x, ATS_GLOBAL const int* edges,
                          ATS_GLOBAL const int* leaves, ATS_GLOBAL const ats_float4* nodes,
                          ATS_GLOBAL const int* levels, int root, float radius, ATS_GLOBAL int* ee) {
  sc_list l;
  sc_list_begin(&l);
  const int s0 = edges[2 * e], s1 = edges[2 * e + 1];
  const ats_vec3 a = sc_v(x[s0]), b = sc_v(x[s1]);
  const sc_box q = sc_box_of_edge(a, b, radius);
  sc_walk w;
  sc_walk_begin(&w, nodes, levels, root, q);
  int u;
  while ((u = sc_walk_next(&w, nodes, levels, q)) >= 0) {
    for (int k = 4; k < 7; ++k) {
      const int f = leaves[8 * u + k];
      if (f < 0 || f == e) continue;
      const int o0 = edges[2 * f], o1 = edges[2 * f + 1];
      if (o0 == s0 || o0 == s1 || o1 == s0 || o1 == s1) continue;
      const ats_vec3 c = sc_v(x[o0]), d = sc_v(x[o1]);
      if (!sc_boxes_overlap(q, sc_box_of_edge(c, d, 0.0f))) continue;
      const ats_pair_geometry g = ats_edge_edge(a, b, c, d);
      if (g.d < radius) sc_list_insert(&l, f, g.d);
    }
  }
  sc_list_store(&l, radius, ee + e * ATS_SC_STRIDE);
}

/* All three queries of leaf u in one walk of the tree: the triangle's own
 * list (per triangle the vertices), the lists of the vertices it owns (per
 * vertex the triangles) and of the edges it owns (per edge the edges), each
 * primitive owned by exactly one leaf (solver/layout/self_contact_layout), so
 * every list has one writer. The walk takes the triangle's box widened by
 * the radius, which holds every owned primitive's widened box; each
 * candidate leaf is then tested against each owned primitive's own box, so
 * each list sees the candidates of its own query in the same order and
 * ends the same as the three queries above, for a third of their walks. */
ATS_FN void sc_query_leaf(int u, ATS_GLOBAL const ats_float4* x, ATS_GLOBAL const int* inc, ATS_GLOBAL const int* tris,
                          ATS_GLOBAL const int* edges, ATS_GLOBAL const int* leaves, ATS_GLOBAL const ats_float4* nodes,
                          ATS_GLOBAL const int* levels, int root, float radius, ATS_GLOBAL int* vt, ATS_GLOBAL int* tv,
                          ATS_GLOBAL int* ee) {
  ATS_GLOBAL const int* f = tris + 4 * u;
  ATS_GLOBAL const int* own = leaves + 8 * u;
  const ats_vec3 a = sc_v(x[f[0]]), b = sc_v(x[f[1]]), c = sc_v(x[f[2]]);
  const sc_box q = sc_box_of_triangle(a, b, c, radius);
  sc_list tri;
  sc_list_begin(&tri);
  /* owned vertices: id (-1: none or not a query), point, widened box */
  int vid[3];
  ats_vec3 vp[3];
  sc_box vq[3];
  sc_list vl[3];
  for (int k = 0; k < 3; ++k) {
    vid[k] = own[k];
    sc_list_begin(&vl[k]);
    if (vid[k] >= 0 && !sc_is_surface(inc, vid[k])) vid[k] = -1;
    vp[k] = vid[k] >= 0 ? sc_v(x[vid[k]]) : a;
    vq[k] = sc_box_of_point(vp[k], radius);
  }
  /* owned edges: id, ends, widened box */
  int eid[3], e0[3], e1[3];
  ats_vec3 ea[3], eb[3];
  sc_box eq[3];
  sc_list el[3];
  for (int k = 0; k < 3; ++k) {
    eid[k] = own[4 + k];
    sc_list_begin(&el[k]);
    e0[k] = eid[k] >= 0 ? edges[2 * eid[k]] : -1;
    e1[k] = eid[k] >= 0 ? edges[2 * eid[k] + 1] : -1;
    ea[k] = eid[k] >= 0 ? sc_v(x[e0[k]]) : a;
    eb[k] = eid[k] >= 0 ? sc_v(x[e1[k]]) : a;
    eq[k] = sc_box_of_edge(ea[k], eb[k], radius);
  }
  sc_walk w;
  sc_walk_begin(&w, nodes, levels, root, q);
  int o;
  while ((o = sc_walk_next(&w, nodes, levels, q)) >= 0) {
    ATS_GLOBAL const int* g = tris + 4 * o;
    ATS_GLOBAL const int* theirs = leaves + 8 * o;
    const sc_box ob = sc_node_box(nodes, o);
    /* per triangle the vertices: the vertices leaf o owns, near triangle u */
    for (int k = 0; k < 3; ++k) {
      const int v = theirs[k];
      if (v < 0 || v == f[0] || v == f[1] || v == f[2]) continue;
      const ats_vec3 p = sc_v(x[v]);
      if (!sc_box_holds(q, p)) continue;
      const ats_pair_geometry pg = ats_point_triangle(p, a, b, c);
      if (pg.d < radius) sc_list_insert(&tri, v, pg.d);
    }
    /* per vertex the triangles: triangle o, near each vertex u owns (its
     * corners read once for all of them) */
    int near = 0;
    for (int k = 0; k < 3; ++k) {
      const int v = vid[k];
      if (v >= 0 && g[0] != v && g[1] != v && g[2] != v && sc_boxes_overlap(ob, vq[k])) near |= 1 << k;
    }
    if (near) {
      const ats_vec3 ga = sc_v(x[g[0]]), gb = sc_v(x[g[1]]), gc = sc_v(x[g[2]]);
      for (int k = 0; k < 3; ++k) {
        if (!(near & (1 << k))) continue;
        const ats_pair_geometry pg = ats_point_triangle(vp[k], ga, gb, gc);
        if (pg.d < radius) sc_list_insert(&vl[k], o, pg.d);
      }
    }
    /* per edge the edges: the edges leaf o owns, near each edge u owns (each
     * candidate read once for all of them; a list sees its candidates in
     * the same order either way) */
    near = 0;
    for (int k = 0; k < 3; ++k)
      if (eid[k] >= 0 && sc_boxes_overlap(ob, eq[k])) near |= 1 << k;
    for (int m = 4; near && m < 7; ++m) {
      const int h = theirs[m];
      if (h < 0) continue;
      const int o0 = edges[2 * h], o1 = edges[2 * h + 1];
      const ats_vec3 p0 = sc_v(x[o0]), p1 = sc_v(x[o1]);
      const sc_box hb = sc_box_of_edge(p0, p1, 0.0f);
      for (int k = 0; k < 3; ++k) {
        if (!(near & (1 << k)) || h == eid[k]) continue;
        if (o0 == e0[k] || o0 == e1[k] || o1 == e0[k] || o1 == e1[k] || !sc_boxes_overlap(eq[k], hb)) continue;
        const ats_pair_geometry pg = ats_edge_edge(ea[k], eb[k], p0, p1);
        if (pg.d < radius) sc_list_insert(&el[k], h, pg.d);
      }
    }
  }
  sc_list_store(&tri, radius, tv + u * ATS_SC_STRIDE);
  for (int k = 0; k < 3; ++k) {
    if (own[k] >= 0) sc_list_store(&vl[k], radius, vt + own[k] * ATS_SC_STRIDE);
    if (eid[k] >= 0) sc_list_store(&el[k], radius, ee + eid[k] * ATS_SC_STRIDE);
  }
}

/* When the lists are rebuilt. A frame's first substep detects (the
 * frame_state buffer `state` is restored then: state[0] = 0), on x_t with
 * the radius R_det = r_max (contact.query_radius, 3 r by default), and
 * remembers x_t as x_det. A later substep of the frame keeps the lists while
 * they still hold every pair it needs: with D the largest displacement of
 * any surface vertex since x_det, a pair closer than R at x_t was closer
 * than R + 2 D at x_det, so the lists serve while R + 2 D <= R_det. R ties
 * the substep's need to its motion: VBD's bound keeps each vertex within
 * gamma R (gamma = 0.4) of x_t, so an unlisted pair stays at least
 * (1 - 2 gamma) R apart (no crossing, for any R); R >= 5 delta keeps the
 * bound from slowing the fastest predicted step (it may double), R >= r +
 * 2.5 delta keeps a pair closing at the predicted speed from reaching the
 * thickness r unlisted, and R >= 1.5 r keeps touching pairs listed; delta
 * is the largest predicted step |x~ - x_t| of any surface vertex.
 * state: [0] lists valid, [1] detect in this substep, [2] R_det (float
 * bits), [3] D (float bits), [4] detections in this frame. */
#define ATS_SC_MOTION_BLOCK 256
#define ATS_SC_STATE_INTS 8

/* Block b of ATS_SC_MOTION_BLOCK particles: [2 b] the largest |x_t - x_det|,
 * [2 b + 1] the largest |x~ - x_t| of its surface vertices. */
ATS_FN void sc_block_motion(int b, ATS_GLOBAL const ats_float4* x_det, ATS_GLOBAL const ats_float4* x_start,
                            ATS_GLOBAL const ats_float4* x_guess, ATS_GLOBAL const int* inc, int n,
                            ATS_GLOBAL float* block_max) {
  float moved = 0.0f, step = 0.0f;
  const int end = (b + 1) * ATS_SC_MOTION_BLOCK < n ? (b + 1) * ATS_SC_MOTION_BLOCK : n;
  for (int i = b * ATS_SC_MOTION_BLOCK; i < end; ++i) {
    if (!sc_is_surface(inc, i)) continue;
    moved = fmax(moved, ats_length(ats_sub(sc_v(x_start[i]), sc_v(x_det[i]))));
    step = fmax(step, ats_length(ats_sub(sc_v(x_guess[i]), sc_v(x_start[i]))));
  }
  block_max[2 * b] = moved;
  block_max[2 * b + 1] = step;
}

/* The radius a substep needs for its largest predicted step delta. */
ATS_FN float sc_needed_radius(float delta, float r, float r_max) {
  return fmin(fmax(1.5f * r, fmax(r + 2.5f * delta, 5.0f * delta)), r_max);
}

ATS_FN void sc_decide(ATS_GLOBAL const float* block_max, int blocks, float r, float r_max, ATS_GLOBAL int* state) {
  float moved = 0.0f, delta = 0.0f;
  for (int b = 0; b < blocks; ++b) {
    moved = fmax(moved, block_max[2 * b]);
    delta = fmax(delta, block_max[2 * b + 1]);
  }
  const int detect = state[0] == 0 || sc_needed_radius(delta, r, r_max) + 2.0f * moved > sc_bits_float(state[2]);
  state[0] = 1;
  state[1] = detect;
  if (detect) {
    state[2] = sc_float_bits(r_max);
    state[3] = sc_float_bits(0.0f);
    state[4] += 1;
  } else {
    state[3] = sc_float_bits(moved);
  }
}

/* The nearest any primitive vertex i does not have listed can be: the
 * smallest horizon of its lists (as a point, through its triangles, through
 * its edges) less twice the displacement D since the lists were made. */
ATS_FN float sc_unlisted_distance(int i, ATS_GLOBAL const int* inc, int n, ATS_GLOBAL const int* vt,
                                  ATS_GLOBAL const int* tv, ATS_GLOBAL const int* ee, float moved) {
  float d = sc_bits_float(vt[i * ATS_SC_STRIDE + 1]);
  for (int k = inc[i]; k < inc[i + 1]; ++k) d = fmin(d, sc_bits_float(tv[inc[k] * ATS_SC_STRIDE + 1]));
  for (int k = inc[n + 1 + i]; k < inc[n + 2 + i]; ++k) d = fmin(d, sc_bits_float(ee[inc[k] * ATS_SC_STRIDE + 1]));
  return d - 2.0f * moved;
}


/* The distances of a list's entries at x, once per substep: out[2 + m]
 * entry m's, out[0] the smallest (1e30 for an empty list). The bound and the
 * near lists read them, so each listed pair's geometry is evaluated once
 * here rather than by each of its vertices. Same layout as the lists. */
ATS_FN void sc_store_distances(ATS_GLOBAL const int* list, const float* d, ATS_GLOBAL float* out) {
  float least = 1e30f;
  for (int m = 0; m < list[0]; ++m) {
    out[2 + m] = d[m];
    least = fmin(least, d[m]);
  }
  out[0] = least;
}

ATS_FN void sc_vertex_distances(int i, ATS_GLOBAL const ats_float4* x, ATS_GLOBAL const int* tris,
                                ATS_GLOBAL const int* vt, ATS_GLOBAL float* vt_d) {
  ATS_GLOBAL const int* l = vt + i * ATS_SC_STRIDE;
  float d[ATS_SC_CAPACITY];
  const ats_vec3 p = sc_v(x[i]);
  for (int m = 0; m < l[0]; ++m) {
    ATS_GLOBAL const int* f = tris + 4 * l[2 + m];
    d[m] = ats_point_triangle(p, sc_v(x[f[0]]), sc_v(x[f[1]]), sc_v(x[f[2]])).d;
  }
  sc_store_distances(l, d, vt_d + i * ATS_SC_STRIDE);
}

ATS_FN void sc_triangle_distances(int t, ATS_GLOBAL const ats_float4* x, ATS_GLOBAL const int* tris,
                                  ATS_GLOBAL const int* tv, ATS_GLOBAL float* tv_d) {
  ATS_GLOBAL const int* l = tv + t * ATS_SC_STRIDE;
  ATS_GLOBAL const int* f = tris + 4 * t;
  float d[ATS_SC_CAPACITY];
  const ats_vec3 a = sc_v(x[f[0]]), b = sc_v(x[f[1]]), c = sc_v(x[f[2]]);
  for (int m = 0; m < l[0]; ++m) d[m] = ats_point_triangle(sc_v(x[l[2 + m]]), a, b, c).d;
  sc_store_distances(l, d, tv_d + t * ATS_SC_STRIDE);
}

ATS_FN void sc_edge_distances(int e, ATS_GLOBAL const ats_float4* x, ATS_GLOBAL const int* edges,
                              ATS_GLOBAL const int* ee, ATS_GLOBAL float* ee_d) {
  ATS_GLOBAL const int* l = ee + e * ATS_SC_STRIDE;
  float d[ATS_SC_CAPACITY];
  const ats_vec3 a = sc_v(x[edges[2 * e]]), b = sc_v(x[edges[2 * e + 1]]);
  for (int m = 0; m < l[0]; ++m) {
    const int o = l[2 + m];
    d[m] = ats_edge_edge(a, b, sc_v(x[edges[2 * o]]), sc_v(x[edges[2 * o + 1]])).d;
  }
  sc_store_distances(l, d, ee_d + e * ATS_SC_STRIDE);
}

/* VBD's conservative displacement bound of vertex i (§3.7): gamma times the
 * distance to the nearest primitive it could meet, on x_t: its listed pairs'
 * distances now (as a point, through its triangles, through its edges), and
 * what its lists' horizons leave for the rest (sc_unlisted_distance). */
ATS_FN float sc_vertex_bound(int i, ATS_GLOBAL const int* inc, int n, ATS_GLOBAL const int* vt,
                             ATS_GLOBAL const int* tv, ATS_GLOBAL const int* ee, ATS_GLOBAL const float* vt_d,
                             ATS_GLOBAL const float* tv_d, ATS_GLOBAL const float* ee_d, float moved, float gamma) {
  if (!sc_is_surface(inc, i)) return 1e30f;
  float d = fmin(sc_unlisted_distance(i, inc, n, vt, tv, ee, moved), vt_d[i * ATS_SC_STRIDE]);
  for (int k = inc[i]; k < inc[i + 1]; ++k) d = fmin(d, tv_d[inc[k] * ATS_SC_STRIDE]);
  for (int k = inc[n + 1 + i]; k < inc[n + 2 + i]; ++k) d = fmin(d, ee_d[inc[k] * ATS_SC_STRIDE]);
  return gamma * fmax(d, 0.0f);
}

/* The near lists: the entries of a list that can come within the thickness
 * r in this substep. Every vertex stays within its bound b of x_t while a
 * substep's solve evaluates the pairs (VBD truncates each step to it, XPBD,
 * JPGD and SOSD clamp to it before each evaluation), and a pair's distance
 * moves by at most the largest bound on each of its two sides, so an entry
 * with d(x_t) - b_first - b_second >= r stays out of the contact energy and
 * the constraints the whole substep. The iterations and friction read the
 * near lists. Same layout as the lists ([1]: the list's horizon). */
ATS_FN float sc_side_bound(ATS_GLOBAL const float* bound, int a, int b, int c) {
  const float m = fmax(bound[a], bound[b]);
  return c >= 0 ? fmax(m, bound[c]) : m;
}

ATS_FN void sc_near_store(ATS_GLOBAL const int* list, const int* keep, ATS_GLOBAL int* out) {
  int count = 0;
  for (int m = 0; m < list[0]; ++m)
    if (keep[m]) out[2 + count++] = list[2 + m];
  out[0] = count;
  out[1] = list[1];
}

ATS_FN void sc_near_vertex(int i, ATS_GLOBAL const int* tris, ATS_GLOBAL const int* vt, ATS_GLOBAL const float* vt_d,
                           ATS_GLOBAL const float* bound, float r, ATS_GLOBAL int* vt_near) {
  ATS_GLOBAL const int* l = vt + i * ATS_SC_STRIDE;
  ATS_GLOBAL const float* d = vt_d + i * ATS_SC_STRIDE;
  int keep[ATS_SC_CAPACITY];
  for (int m = 0; m < l[0]; ++m) {
    ATS_GLOBAL const int* f = tris + 4 * l[2 + m];
    keep[m] = d[2 + m] - bound[i] - sc_side_bound(bound, f[0], f[1], f[2]) < r;
  }
  sc_near_store(l, keep, vt_near + i * ATS_SC_STRIDE);
}

ATS_FN void sc_near_triangle(int t, ATS_GLOBAL const int* tris, ATS_GLOBAL const int* tv, ATS_GLOBAL const float* tv_d,
                             ATS_GLOBAL const float* bound, float r, ATS_GLOBAL int* tv_near) {
  ATS_GLOBAL const int* l = tv + t * ATS_SC_STRIDE;
  ATS_GLOBAL const float* d = tv_d + t * ATS_SC_STRIDE;
  ATS_GLOBAL const int* f = tris + 4 * t;
  int keep[ATS_SC_CAPACITY];
  const float reach = sc_side_bound(bound, f[0], f[1], f[2]);
  for (int m = 0; m < l[0]; ++m) keep[m] = d[2 + m] - reach - bound[l[2 + m]] < r;
  sc_near_store(l, keep, tv_near + t * ATS_SC_STRIDE);
}

ATS_FN void sc_near_edge(int e, ATS_GLOBAL const int* edges, ATS_GLOBAL const int* ee, ATS_GLOBAL const float* ee_d,
                         ATS_GLOBAL const float* bound, float r, ATS_GLOBAL int* ee_near) {
  ATS_GLOBAL const int* l = ee + e * ATS_SC_STRIDE;
  ATS_GLOBAL const float* d = ee_d + e * ATS_SC_STRIDE;
  int keep[ATS_SC_CAPACITY];
  const float reach = sc_side_bound(bound, edges[2 * e], edges[2 * e + 1], -1);
  for (int m = 0; m < l[0]; ++m) {
    const int o = l[2 + m];
    keep[m] = d[2 + m] - reach - sc_side_bound(bound, edges[2 * o], edges[2 * o + 1], -1) < r;
  }
  sc_near_store(l, keep, ee_near + e * ATS_SC_STRIDE);
}

#endif
