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
 * of its incident edges; then the lists. */
ATS_FN int sc_is_surface(ATS_GLOBAL const int* inc, int i) { return inc[i + 1] > inc[i]; }

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
  ats_vec3 a, b, c;
  sc_box q;
  sc_list tri;
  int vid[3]; /* owned vertices: id (-1: none or not a query), point, widened box */
  ats_vec3 vp[3];
  sc_box vq[3];
  sc_list vl[3];
  int eid[3], e0[3], e1[3]; /* owned edges: id, ends, widened box */
  ats_vec3 ea[3], eb[3];
  sc_box eq[3];
  sc_list el[3];
} sc_leaf_query;

ATS_FN void sc_leaf_begin(sc_leaf_query* lq, int u, ATS_GLOBAL const ats_float4* x, ATS_GLOBAL const int* inc,
                          ATS_GLOBAL const int* tris, ATS_GLOBAL const int* edges, ATS_GLOBAL const int* leaves,
                          float radius) {
  ATS_GLOBAL const int* f = tris + 4 * u;
  ATS_GLOBAL const int* own = leaves + 8 * u;
  lq->u = u;
  for (int k = 0; k < 3; ++k) lq->f[k] = f[k];
  lq->a = sc_v(x[f[0]]);
  lq->b = sc_v(x[f[1]]);
  lq->c = sc_v(x[f[2]]);
  lq->q = sc_box_of_triangle(lq->a, lq->b, lq->c, radius);
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
  }
}

/* Candidate leaf o (its box overlaps q). */
ATS_FN void sc_leaf_candidate(sc_leaf_query* lq, int o, ATS_GLOBAL const ats_float4* x, ATS_GLOBAL const int* tris,
                              ATS_GLOBAL const int* edges, ATS_GLOBAL const int* leaves,
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
    if (pg.d < radius) sc_list_insert(&lq->tri, v, pg.d);
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
    for (int k = 0; k < 3; ++k) {
      if (!(near & (1 << k))) continue;
      const ats_pair_geometry pg = ats_point_triangle(lq->vp[k], ga, gb, gc);
      if (pg.d < radius) sc_list_insert(&lq->vl[k], o, pg.d);
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
      const ats_pair_geometry pg = ats_edge_edge(lq->ea[k], lq->eb[k], p0, p1);
      if (pg.d < radius) sc_list_insert(&lq->el[k], h, pg.d);
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
ATS_FN void sc_query_leaf(int u, ATS_GLOBAL const ats_float4* x, ATS_GLOBAL const int* inc, ATS_GLOBAL const int* tris,
                          ATS_GLOBAL const int* edges, ATS_GLOBAL const int* leaves, ATS_GLOBAL const ats_float4* nodes,
                          ATS_GLOBAL const int* levels, int root, float radius, ATS_GLOBAL int* vt, ATS_GLOBAL int* tv,
                          ATS_GLOBAL int* ee) {
  sc_leaf_query lq;
  sc_leaf_begin(&lq, u, x, inc, tris, edges, leaves, radius);
  sc_walk w;
  sc_walk_begin(&w, nodes, levels, root, lq.q);
  int o;
  while ((o = sc_walk_next(&w, nodes, levels, lq.q)) >= 0)
    sc_leaf_candidate(&lq, o, x, tris, edges, leaves, nodes, radius);
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
ATS_FN void sc_query_group(int g, int leaf_count, ATS_GLOBAL const ats_float4* x, ATS_GLOBAL const int* inc,
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
      sc_query_leaf(u, x, inc, tris, edges, leaves, nodes, levels, root, radius, vt, tv, ee);
      continue;
    }
    sc_leaf_query lq;
    sc_leaf_begin(&lq, u, x, inc, tris, edges, leaves, radius);
    for (int k = 0; k < count; ++k)
      if (sc_boxes_overlap(sc_node_box(nodes, cand[k]), lq.q))
        sc_leaf_candidate(&lq, cand[k], x, tris, edges, leaves, nodes, radius);
    sc_leaf_end(&lq, radius, leaves, vt, tv, ee);
  }
}

/* When the lists are rebuilt. A frame's first substep detects (the
 * frame_state buffer `state` is restored then: state[0] = 0), on x_t with
 * the radius R_det = r_max (contact.query_radius, 3 r by default), and
 * remembers x_t as x_det. Distances between primitives do not change when
 * every vertex moves by one common vector, so motion is measured relative
 * to one: with u_i = x_t - x_det (since the lists were made) and s_i = x~ -
 * x_t (this substep's predicted step) over the surface vertices, D and
 * delta are the half diagonals of the boxes holding every u_i and every s_i
 * (each u_i is within D of its box's centre, so any two differ by at most
 * 2 D). A later substep of the frame keeps the lists while they still hold
 * every pair it needs: a pair closer than R at x_t was closer than R + 2 D
 * at x_det, so the lists serve while R + 2 D <= R_det. R ties the
 * substep's need to its relative motion: VBD's bound keeps each vertex
 * within gamma R of x_t, so an unlisted pair stays at least (1 - 2 gamma) R
 * apart (no crossing, for any R); R >= 5 delta keeps the bound from slowing
 * the relative predicted step (it may double), R >= r + 2.5 delta keeps a
 * pair closing at the predicted speed from reaching the thickness r
 * unlisted, and R >= 1.5 r keeps touching pairs listed. A cloth falling or
 * carried as a whole keeps its lists.
 * state: [0] lists valid, [1] detect in this substep, [2] R_det (float
 * bits), [3] D (float bits), [4] detections in this frame. */
#define ATS_SC_MOTION_BLOCK 256
#define ATS_SC_MOTION_FLOATS 12
#define ATS_SC_STATE_INTS 8

ATS_FN void sc_box_add(sc_box* b, ats_vec3 p) {
  b->lo = sc_min3(b->lo, p);
  b->hi = sc_max3(b->hi, p);
}
ATS_FN sc_box sc_box_empty(void) {
  sc_box b;
  b.lo = ats_v3(1e30f, 1e30f, 1e30f);
  b.hi = ats_v3(-1e30f, -1e30f, -1e30f);
  return b;
}
ATS_FN void sc_store_box(ATS_GLOBAL float* out, sc_box b) {
  out[0] = b.lo.x;
  out[1] = b.lo.y;
  out[2] = b.lo.z;
  out[3] = b.hi.x;
  out[4] = b.hi.y;
  out[5] = b.hi.z;
}
ATS_FN sc_box sc_load_box(ATS_GLOBAL const float* in) {
  sc_box b;
  b.lo = ats_v3(in[0], in[1], in[2]);
  b.hi = ats_v3(in[3], in[4], in[5]);
  return b;
}
/* Half the diagonal of a box (0 for an empty one). */
ATS_FN float sc_half_diagonal(sc_box b) { return b.hi.x < b.lo.x ? 0.0f : 0.5f * ats_length(ats_sub(b.hi, b.lo)); }

/* Block b of ATS_SC_MOTION_BLOCK particles: block_max[12 b ..]: the box of
 * x_t - x_det, then the box of x~ - x_t, over its surface vertices. */
ATS_FN void sc_block_motion(int b, ATS_GLOBAL const ats_float4* x_det, ATS_GLOBAL const ats_float4* x_start,
                            ATS_GLOBAL const ats_float4* x_guess, ATS_GLOBAL const int* inc, int n,
                            ATS_GLOBAL float* block_max) {
  sc_box moved = sc_box_empty(), step = sc_box_empty();
  const int end = (b + 1) * ATS_SC_MOTION_BLOCK < n ? (b + 1) * ATS_SC_MOTION_BLOCK : n;
  for (int i = b * ATS_SC_MOTION_BLOCK; i < end; ++i) {
    if (!sc_is_surface(inc, i)) continue;
    sc_box_add(&moved, ats_sub(sc_v(x_start[i]), sc_v(x_det[i])));
    sc_box_add(&step, ats_sub(sc_v(x_guess[i]), sc_v(x_start[i])));
  }
  sc_store_box(block_max + ATS_SC_MOTION_FLOATS * b, moved);
  sc_store_box(block_max + ATS_SC_MOTION_FLOATS * b + 6, step);
}

/* The radius a substep needs for its largest relative predicted step delta. */
ATS_FN float sc_needed_radius(float delta, float r, float r_max) {
  return fmin(fmax(1.5f * r, fmax(r + 2.5f * delta, 5.0f * delta)), r_max);
}

ATS_FN void sc_decide(ATS_GLOBAL const float* block_max, int blocks, float r, float r_max, ATS_GLOBAL int* state) {
  sc_box moved_box = sc_box_empty(), step_box = sc_box_empty();
  for (int b = 0; b < blocks; ++b) {
    const sc_box m = sc_load_box(block_max + ATS_SC_MOTION_FLOATS * b);
    const sc_box s = sc_load_box(block_max + ATS_SC_MOTION_FLOATS * b + 6);
    moved_box.lo = sc_min3(moved_box.lo, m.lo);
    moved_box.hi = sc_max3(moved_box.hi, m.hi);
    step_box.lo = sc_min3(step_box.lo, s.lo);
    step_box.hi = sc_max3(step_box.hi, s.hi);
  }
  const float moved = sc_half_diagonal(moved_box), delta = sc_half_diagonal(step_box);
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
 * near lists. Same layout as the lists ([1]: the list's horizon, but see
 * sc_near_vertex). */
ATS_FN float sc_side_bound(ATS_GLOBAL const float* bound, int a, int b, int c) {
  const float m = fmax(bound[a], bound[b]);
  return c >= 0 ? fmax(m, bound[c]) : m;
}

ATS_FN int sc_near_store(ATS_GLOBAL const int* list, const int* keep, ATS_GLOBAL int* out) {
  int count = 0;
  for (int m = 0; m < list[0]; ++m)
    if (keep[m]) out[2 + count++] = list[2 + m];
  out[0] = count;
  out[1] = list[1];
  return count;
}

/* Vertex i's near list, after its triangles' and edges' (sc_near_triangle,
 * sc_near_edge): [1] holds how many near entries vertex i is in, as a point,
 * through its triangles and through its edges, so that a vertex without any
 * skips the gathers (contact/self_contact.cl SC_FOR_EACH_PAIR). */
ATS_FN void sc_near_vertex(int i, ATS_GLOBAL const int* inc, int n, ATS_GLOBAL const int* tris,
                           ATS_GLOBAL const int* vt, ATS_GLOBAL const float* vt_d, ATS_GLOBAL const float* bound,
                           float r, ATS_GLOBAL const int* tv_near, ATS_GLOBAL const int* ee_near,
                           ATS_GLOBAL int* vt_near) {
  ATS_GLOBAL const int* l = vt + i * ATS_SC_STRIDE;
  ATS_GLOBAL const float* d = vt_d + i * ATS_SC_STRIDE;
  int keep[ATS_SC_CAPACITY];
  for (int m = 0; m < l[0]; ++m) {
    ATS_GLOBAL const int* f = tris + 4 * l[2 + m];
    keep[m] = d[2 + m] - bound[i] - sc_side_bound(bound, f[0], f[1], f[2]) < r;
  }
  int total = sc_near_store(l, keep, vt_near + i * ATS_SC_STRIDE);
  for (int k = inc[i]; k < inc[i + 1]; ++k) total += tv_near[inc[k] * ATS_SC_STRIDE];
  for (int k = inc[n + 1 + i]; k < inc[n + 2 + i]; ++k) total += ee_near[inc[k] * ATS_SC_STRIDE];
  vt_near[i * ATS_SC_STRIDE + 1] = total;
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
