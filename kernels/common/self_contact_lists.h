/* The pair lists between substeps (kernels/contact/self_contact.cl), in the
 * common subset of C, C++ and OpenCL C like common/self_contact_bvh.h, whose
 * lists they keep and read: when a substep rebuilds them (the motion of
 * the surface since they were made, sc_decide), each listed pair's
 * distance once per substep, the per-vertex bound, and the near lists the
 * iterations and friction read. */
#ifndef ATS_SELF_CONTACT_LISTS_H
#define ATS_SELF_CONTACT_LISTS_H

#include "common/self_contact_bvh.h"

/* Which lists are made anew, per block of ATS_SC_BLOCK leaves (leaf
 * order, so a block is a patch of surface) and its lists: its triangles',
 * and those of the vertices and edges its leaves own
 * (solver/layout/self_contact_layout). A block makes its lists on x_t with
 * the radius R_det = r_max (contact.query_radius, 3 r by default); a
 * list's horizon h (sc_list_store) says that every primitive it does not
 * hold is at least h away. The block then keeps rho, the radius its lists
 * still vouch for: R_det when made, less the erosion e, the most any of
 * its primitives can have closed on another since x_det. x_det is where
 * every block's rho was last taken stock of: x_t of the last substep in
 * which some block made its lists (sc_decide_any; rho0 holds each block's
 * rho there). With u_i = x_t - x_det over the surface vertices, U_A the box
 * of u over block A's triangles' corners and X_A the box of those corners
 * at x_t: the corners hold every vertex of the primitives whose lists A
 * owns, and every primitive a list names is owned by some block's leaf, so
 * lies in that block's boxes. A pair of A's and block c's primitives
 * closed by at most the largest |u_a - u_c| over the two boxes
 * (sc_boxes_most_apart), and one of a block c whose X_c is farther than
 * rho0 from X_A is farther than rho0 at x_t already; so e is the largest of
 * the former over the blocks within rho0 (A among them), rho = rho0 - e,
 * and each list of A holds every primitive closer than its horizon less
 * R_det - rho (sc_list_reach). Measured since x_det rather than summed
 * substep by substep, a jitter back and forth does not add up. A block
 * makes its lists anew when rho falls below R, the radius it needs in the
 * substep (sc_needed_radius, from the largest relative predicted step
 * delta between it and the blocks near it): VBD's bound keeps each vertex within gamma R of
 * x_t, so an unlisted pair stays at least (1 - 2 gamma) R apart (no
 * crossing, for any R); R >= 5 delta keeps the bound from slowing the
 * relative predicted step (it may double), R >= r + 2.5 delta keeps a pair
 * closing at the predicted speed from reaching the thickness r unlisted,
 * and R >= 1.5 r keeps touching pairs listed. A block whose surface moves
 * with its neighbours (a cloth falling, carried or at rest) keeps its
 * lists, from one frame to the next too; only the patches where the
 * surface moves against its neighbours make theirs anew (a cloth driven
 * into a funnel: its layers in the spout's mouth, not on the rim).
 * The lists, their packed counts, rho0, x_det and `state` are carried with
 * the positions (and kept in a checkpoint), so a reset (resume, repeats,
 * probes) goes on with the lists it had, bit for bit.
 * state: [0] and [3] unused, [1] some block makes its lists in this
 * substep (so the BVH is refitted and x_det taken), [2] R_det (float bits),
 * [4] substeps that made lists, [5] blocks' lists made, in all. */
#define ATS_SC_BLOCK 256
#define ATS_SC_BLOCK_FLOATS 18
#define ATS_SC_CLUSTER 32
#define ATS_SC_MOTION_BLOCK 256
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

/* The shortest distance between a point of box a and one of box b. */
ATS_FN float sc_boxes_gap(sc_box a, sc_box b) {
  const ats_vec3 g =
      ats_v3(fmax(0.0f, fmax(a.lo.x - b.hi.x, b.lo.x - a.hi.x)), fmax(0.0f, fmax(a.lo.y - b.hi.y, b.lo.y - a.hi.y)),
             fmax(0.0f, fmax(a.lo.z - b.hi.z, b.lo.z - a.hi.z)));
  return ats_length(g);
}
/* The longest distance between a point of box a and one of box b. */
ATS_FN float sc_boxes_most_apart(sc_box a, sc_box b) {
  const ats_vec3 g = ats_v3(fmax(a.hi.x - b.lo.x, b.hi.x - a.lo.x), fmax(a.hi.y - b.lo.y, b.hi.y - a.lo.y),
                            fmax(a.hi.z - b.lo.z, b.hi.z - a.lo.z));
  return ats_length(g);
}

/* Block b (leaves [b B, b B + B), B = ATS_SC_BLOCK) over its triangles'
 * corners, each once (corners[corner_start[b] .. corner_start[b + 1]),
 * made on the host: a third to a fifth of the 3 B corners its triangles
 * name): motion[18 b ..] the box of x_t, of x_t - x_det and of the
 * predicted step x~ - x_t. */
ATS_FN void sc_block_motion(int b, ATS_GLOBAL const ats_float4* x_det, ATS_GLOBAL const ats_float4* x_start,
                            ATS_GLOBAL const ats_float4* x_guess, ATS_GLOBAL const int* corner_start,
                            ATS_GLOBAL const int* corners, ATS_GLOBAL float* motion) {
  sc_box at = sc_box_empty(), moved = sc_box_empty(), step = sc_box_empty();
  for (int j = corner_start[b]; j < corner_start[b + 1]; ++j) {
    const int i = corners[j];
    const ats_vec3 p = sc_v(x_start[i]);
    sc_box_add(&at, p);
    sc_box_add(&moved, ats_sub(p, sc_v(x_det[i])));
    sc_box_add(&step, ats_sub(sc_v(x_guess[i]), p));
  }
  sc_store_box(motion + ATS_SC_BLOCK_FLOATS * b, at);
  sc_store_box(motion + ATS_SC_BLOCK_FLOATS * b + 6, moved);
  sc_store_box(motion + ATS_SC_BLOCK_FLOATS * b + 12, step);
}

/* Cluster k of ATS_SC_CLUSTER blocks (consecutive, so a patch of patches):
 * the box of its blocks' x_t boxes, clusters[6 k ..]. sc_block_decide
 * passes over a cluster farther than its rho0 whole: no block of it can be
 * nearer (the union's gap is at most each member's, in floats too, as min,
 * max and a rounded difference are monotone), so the decision is that of
 * every block against every block, at about 1/ATS_SC_CLUSTER of its cost
 * (2,048 blocks at 262K vertices: 4 M box pairs a substep before). */
ATS_FN void sc_cluster_box(int k, ATS_GLOBAL const float* motion, int blocks, ATS_GLOBAL float* clusters) {
  sc_box u = sc_box_empty();
  const int end = (k + 1) * ATS_SC_CLUSTER < blocks ? (k + 1) * ATS_SC_CLUSTER : blocks;
  for (int c = k * ATS_SC_CLUSTER; c < end; ++c) {
    const sc_box o = sc_load_box(motion + ATS_SC_BLOCK_FLOATS * c);
    u.lo = sc_min3(u.lo, o.lo);
    u.hi = sc_max3(u.hi, o.hi);
  }
  sc_store_box(clusters + 6 * k, u);
}

/* The radius a substep needs for its largest relative predicted step delta. */
ATS_FN float sc_needed_radius(float delta, float r, float r_max) {
  return fmin(fmax(1.5f * r, fmax(r + 2.5f * delta, 5.0f * delta)), r_max);
}

/* Whether block a makes its lists anew (make[a]), and its rho (rho0[a]: at
 * x_det, 0 before its first lists). The radius it needs, R, is from its
 * own relative predicted step delta: half the longest distance between
 * its steps' box and that of a block within rho0 (itself among them). The
 * gap is widened and the erosion grown by 1e-3, far above the rounding of
 * either. */
ATS_FN void sc_block_decide(int a, ATS_GLOBAL const float* motion, ATS_GLOBAL const float* clusters, int blocks,
                            float r, float r_max, ATS_GLOBAL const float* rho0, ATS_GLOBAL float* rho,
                            ATS_GLOBAL int* make) {
  const float start = rho0[a];
  float now = 0.0f;
  int anew = !(start > 0.0f);
  if (!anew) {
    ATS_GLOBAL const float* m = motion + ATS_SC_BLOCK_FLOATS * a;
    const sc_box at = sc_load_box(m), moved = sc_load_box(m + 6), step = sc_load_box(m + 12);
    float e = 0.0f, spread = 0.0f;
    const int cluster_count = (blocks + ATS_SC_CLUSTER - 1) / ATS_SC_CLUSTER;
    for (int k = 0; k < cluster_count; ++k) {
      if (!(sc_boxes_gap(at, sc_load_box(clusters + 6 * k)) <= 1.001f * start)) continue;
      const int end = (k + 1) * ATS_SC_CLUSTER < blocks ? (k + 1) * ATS_SC_CLUSTER : blocks;
      for (int c = k * ATS_SC_CLUSTER; c < end; ++c) {
        ATS_GLOBAL const float* o = motion + ATS_SC_BLOCK_FLOATS * c;
        if (!(sc_boxes_gap(at, sc_load_box(o)) <= 1.001f * start)) continue;
        e = fmax(e, sc_boxes_most_apart(moved, sc_load_box(o + 6)));
        spread = fmax(spread, sc_boxes_most_apart(step, sc_load_box(o + 12)));
      }
    }
    now = start - 1.001f * e;
    anew = !(now >= sc_needed_radius(0.5f * spread, r, r_max));
  }
  make[a] = anew;
  rho[a] = anew ? r_max : now;
}

/* After every block's decision (one work-item): state[1], [2], [4] and
 * [5]; where some block made its lists, x_det becomes x_t (sc_snap) and
 * each block's rho there its rho0. */
ATS_FN void sc_decide_any(ATS_GLOBAL const int* make, int blocks, float r_max, ATS_GLOBAL const float* rho,
                          ATS_GLOBAL float* rho0, ATS_GLOBAL int* state) {
  int count = 0;
  for (int b = 0; b < blocks; ++b) count += make[b];
  state[1] = count > 0;
  state[2] = sc_float_bits(r_max);
  if (count == 0) return;
  state[4] += 1;
  state[5] += count;
  for (int b = 0; b < blocks; ++b) rho0[b] = rho[b];
}

/* The distances of a list's entries at x, once per substep: out[2 + m]
 * entry m's, out[0] the smallest (1e30 for an empty list). The bound and the
 * near lists read them, so each listed pair's geometry is evaluated once
 * here rather than by each of its vertices. Same layout as the lists. And
 * the list's reach, the nearest its primitive can be to any other, listed
 * (the smallest distance) or not (its horizon, which every primitive it
 * does not hold was at least at, less its block's erosion since the lists
 * were made, R_det - rho of sc_block_decide), into reach[id]: one
 * float per list, so that the bound's gather over a vertex's lists reads
 * packed floats rather than a strided list each (sc_vertex_bound). */
ATS_FN float sc_list_reach(float least, float horizon, float eroded) { return fmin(least, horizon - eroded); }
ATS_FN void sc_store_distances(ATS_GLOBAL const int* list, const float* d, ATS_GLOBAL float* out, float eroded,
                               ATS_GLOBAL float* reach) {
  float least = 1e30f;
  for (int m = 0; m < list[0]; ++m) {
    out[2 + m] = d[m];
    least = fmin(least, d[m]);
  }
  out[0] = least;
  *reach = sc_list_reach(least, sc_bits_float(list[1]), eroded);
}
/* An empty list's reach: its horizon is the radius it was made with
 * (sc_list_store), so it needs no read of the list (nor writes its
 * distances, which nothing reads for an empty list); `listed` packs each
 * list's count as the substep that made the list found it, so that the
 * substeps that keep it read 4 bytes per list rather than a strided list
 * header each (most lists are empty). */
ATS_FN float sc_empty_reach(float radius, float eroded) { return sc_list_reach(1e30f, radius, eroded); }

ATS_FN void sc_vertex_distances(int i, ATS_GLOBAL const ats_float4* x, ATS_GLOBAL const int* tris,
                                ATS_GLOBAL const int* vt, ATS_GLOBAL float* vt_d, float eroded,
                                ATS_GLOBAL float* reach) {
  ATS_GLOBAL const int* l = vt + i * ATS_SC_STRIDE;
  float d[ATS_SC_CAPACITY];
  const ats_vec3 p = sc_v(x[i]);
  for (int m = 0; m < l[0]; ++m) {
    ATS_GLOBAL const int* f = tris + 4 * l[2 + m];
    d[m] = ats_point_triangle(p, sc_v(x[f[0]]), sc_v(x[f[1]]), sc_v(x[f[2]])).d;
  }
  sc_store_distances(l, d, vt_d + i * ATS_SC_STRIDE, eroded, reach + i);
}

ATS_FN void sc_triangle_distances(int t, ATS_GLOBAL const ats_float4* x, ATS_GLOBAL const int* tris,
                                  ATS_GLOBAL const int* tv, ATS_GLOBAL float* tv_d, float eroded,
                                  ATS_GLOBAL float* reach) {
  ATS_GLOBAL const int* l = tv + t * ATS_SC_STRIDE;
  ATS_GLOBAL const int* f = tris + 4 * t;
  float d[ATS_SC_CAPACITY];
  const ats_vec3 a = sc_v(x[f[0]]), b = sc_v(x[f[1]]), c = sc_v(x[f[2]]);
  for (int m = 0; m < l[0]; ++m) d[m] = ats_point_triangle(sc_v(x[l[2 + m]]), a, b, c).d;
  sc_store_distances(l, d, tv_d + t * ATS_SC_STRIDE, eroded, reach + t);
}

ATS_FN void sc_edge_distances(int e, ATS_GLOBAL const ats_float4* x, ATS_GLOBAL const int* edges,
                              ATS_GLOBAL const int* ee, ATS_GLOBAL float* ee_d, float eroded, ATS_GLOBAL float* reach) {
  ATS_GLOBAL const int* l = ee + e * ATS_SC_STRIDE;
  float d[ATS_SC_CAPACITY];
  const ats_vec3 a = sc_v(x[edges[2 * e]]), b = sc_v(x[edges[2 * e + 1]]);
  for (int m = 0; m < l[0]; ++m) {
    const int o = l[2 + m];
    d[m] = ats_edge_edge(a, b, sc_v(x[edges[2 * o]]), sc_v(x[edges[2 * o + 1]])).d;
  }
  sc_store_distances(l, d, ee_d + e * ATS_SC_STRIDE, eroded, reach + e);
}

/* VBD's conservative displacement bound of vertex i (§3.7): gamma times the
 * distance to the nearest primitive it could meet, on x_t: the reach of its
 * lists (sc_store_distances), as a point, through its triangles and through
 * its edges: the smallest of the listed pairs' distances and of the lists'
 * horizons, each less its block's erosion. */
ATS_FN float sc_vertex_bound(int i, ATS_GLOBAL const int* inc, int n, ATS_GLOBAL const float* vt_reach,
                             ATS_GLOBAL const float* tv_reach, ATS_GLOBAL const float* ee_reach, float gamma) {
  if (!sc_is_surface(inc, i)) return 1e30f;
  float d = vt_reach[i];
  for (int k = inc[i]; k < inc[i + 1]; ++k) d = fmin(d, tv_reach[inc[k]]);
  for (int k = inc[n + 1 + i]; k < inc[n + 2 + i]; ++k) d = fmin(d, ee_reach[inc[k]]);
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
/* The largest of a per-vertex value (the bound; `moved`, sc_list_apart) over a side's vertices (c < 0: two). */
ATS_FN float sc_side_bound(ATS_GLOBAL const float* bound, int a, int b, int c) {
  const float m = fmax(bound[a], bound[b]);
  return c >= 0 ? fmax(m, bound[c]) : m;
}

/* Whether a near list's every entry is still apart, without reading them
 * (contact/self_contact.cl: sc_still_apart skips an entry when
 * fl(fl(d0 - m0) - m1) > reach, d0 its distance at x_t, m0 and m1 the
 * largest displacement since x_t on its first and second side). least is
 * the list's smallest d0 (d0[0], sc_store_distances); first and second
 * are at least every entry's m0 and m1 (the list's own primitive's side by
 * its vertices' largest, sc_side_bound; the other side's by the largest of
 * every surface vertex; a NaN among them fails the test and skips
 * nothing). fl(a -
 * b) grows with a and falls with b, so every entry's test is at least this
 * one's, and the skip is the entry by entry skip's result, bit for bit.
 * Most near lists of layered cloth hold pairs a thickness or more apart
 * that move far less than their bound within a substep. */
ATS_FN int sc_list_apart(float least, float first, float second, float reach) {
  return least > reach && least - first - second > reach;
}

/* The kept entries' ids into out, and their distances at x_t moved to the
 * front of the list's distances d (in place: the bound has read them), so
 * that d[2 + k] is near entry k's; the iterations and friction skip an
 * entry whose pair cannot have come within reach (sc_still_apart). */
ATS_FN int sc_near_store(ATS_GLOBAL const int* list, const int* keep, ATS_GLOBAL int* out, ATS_GLOBAL float* d) {
  int count = 0;
  for (int m = 0; m < list[0]; ++m) {
    if (!keep[m]) continue;
    d[2 + count] = d[2 + m];
    out[2 + count++] = list[2 + m];
  }
  out[0] = count;
  out[1] = list[1];
  return count;
}

/* The near entries of vertex i's triangles and edges (their counts packed). */
ATS_FN int sc_near_through(int i, ATS_GLOBAL const int* inc, int n, ATS_GLOBAL const int* tv_count,
                           ATS_GLOBAL const int* ee_count) {
  int total = 0;
  for (int k = inc[i]; k < inc[i + 1]; ++k) total += tv_count[inc[k]];
  for (int k = inc[n + 1 + i]; k < inc[n + 2 + i]; ++k) total += ee_count[inc[k]];
  return total;
}

/* Vertex i's near list, after its triangles' and edges' (sc_near_triangle,
 * sc_near_edge, which leave their counts packed in tv_count, ee_count): [1]
 * holds how many near entries vertex i is in, as a point, through its
 * triangles and through its edges, so that a vertex without any skips the
 * gathers (contact/self_contact.cl SC_FOR_EACH_PAIR); vt_count[i] and
 * vt_total[i] hold its own count and that total packed, for the passes
 * that skip the lists without near entries (XPBD's projection). */
ATS_FN void sc_near_vertex(int i, ATS_GLOBAL const int* inc, int n, ATS_GLOBAL const int* tris,
                           ATS_GLOBAL const int* vt, ATS_GLOBAL float* vt_d, ATS_GLOBAL const float* bound, float r,
                           ATS_GLOBAL const int* tv_count, ATS_GLOBAL const int* ee_count, ATS_GLOBAL int* vt_near,
                           ATS_GLOBAL int* vt_count, ATS_GLOBAL int* vt_total) {
  ATS_GLOBAL const int* l = vt + i * ATS_SC_STRIDE;
  ATS_GLOBAL float* d = vt_d + i * ATS_SC_STRIDE;
  int keep[ATS_SC_CAPACITY];
  for (int m = 0; m < l[0]; ++m) {
    ATS_GLOBAL const int* f = tris + 4 * l[2 + m];
    keep[m] = d[2 + m] - bound[i] - sc_side_bound(bound, f[0], f[1], f[2]) < r;
  }
  const int own = sc_near_store(l, keep, vt_near + i * ATS_SC_STRIDE, d);
  const int total = own + sc_near_through(i, inc, n, tv_count, ee_count);
  vt_near[i * ATS_SC_STRIDE + 1] = total;
  vt_count[i] = own;
  vt_total[i] = total;
}

ATS_FN void sc_near_triangle(int t, ATS_GLOBAL const int* tris, ATS_GLOBAL const int* tv, ATS_GLOBAL float* tv_d,
                             ATS_GLOBAL const float* bound, float r, ATS_GLOBAL int* tv_near,
                             ATS_GLOBAL int* tv_count) {
  ATS_GLOBAL const int* l = tv + t * ATS_SC_STRIDE;
  ATS_GLOBAL float* d = tv_d + t * ATS_SC_STRIDE;
  ATS_GLOBAL const int* f = tris + 4 * t;
  int keep[ATS_SC_CAPACITY];
  const float reach = sc_side_bound(bound, f[0], f[1], f[2]);
  for (int m = 0; m < l[0]; ++m) keep[m] = d[2 + m] - reach - bound[l[2 + m]] < r;
  tv_count[t] = sc_near_store(l, keep, tv_near + t * ATS_SC_STRIDE, d);
}

ATS_FN void sc_near_edge(int e, ATS_GLOBAL const int* edges, ATS_GLOBAL const int* ee, ATS_GLOBAL float* ee_d,
                         ATS_GLOBAL const float* bound, float r, ATS_GLOBAL int* ee_near, ATS_GLOBAL int* ee_count) {
  ATS_GLOBAL const int* l = ee + e * ATS_SC_STRIDE;
  ATS_GLOBAL float* d = ee_d + e * ATS_SC_STRIDE;
  int keep[ATS_SC_CAPACITY];
  const float reach = sc_side_bound(bound, edges[2 * e], edges[2 * e + 1], -1);
  for (int m = 0; m < l[0]; ++m) {
    const int o = l[2 + m];
    keep[m] = d[2 + m] - reach - sc_side_bound(bound, edges[2 * o], edges[2 * o + 1], -1) < r;
  }
  ee_count[e] = sc_near_store(l, keep, ee_near + e * ATS_SC_STRIDE, d);
}

#endif
