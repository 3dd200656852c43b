/* Contact between simulated surfaces (scene `contact: {self: true}`):
 * collision detection at the start of every substep, on x_t (Chen et al.
 * 2024, VBD §3.7), as tasks that range over independent elements:
 *   sc_motion, sc_clusters, sc_decide_*: per block of surface whether the lists it
 *     made earlier still serve (its motion against its neighbours',
 *     common/self_contact_lists.h sc_block_decide);
 *   sc_leaf_boxes, sc_refit_level, sc_refit_top: refit the BVH over the
 *     surface triangles (built once on the host, solver/layout/
 *     self_contact_layout), one task per level up to the small top levels;
 *   sc_query_groups: per vertex the triangles, per triangle the vertices and
 *     per edge the edges within the query radius (incident pairs
 *     excluded), the ATS_SC_CAPACITY nearest of each, for the primitives
 *     each leaf owns, one walk per group of leaves (these only where a
 *     block makes its lists anew);
 *   sc_*_distances_task: every listed pair's distance at x_t, once;
 *   sc_bound: per vertex the conservative displacement bound of VBD:
 *     gamma times the distance to the nearest primitive it could meet
 *     (as a point, through its triangles, through its edges), so that no
 *     vertex passes through a triangle within the substep;
 *   sc_near_*: the near lists, the entries that can come within the
 *     thickness in this substep, which the iterations and friction read;
 *   sc_clamp: a position held within its bound of x_t (the first guess;
 *     every solve step of the vertex methods does the same);
 *   sc_pair_lambdas_*, then sc_project: XPBD's inequality constraints
 *     d >= r of every listed pair, per list entry, then Jacobi-averaged per
 *     vertex;
 *   sc_friction (then sc_apply): Coulomb friction between the surfaces,
 *     after the iterations, every method (contact/self_contact_friction.cl,
 *     included at the end).
 * The pair lists: per primitive ATS_SC_STRIDE ints, [count, horizon (float
 * bits), ids of the nearest first]. */
#include "common/ats_math.h"
#include "common/collider_distance.h"
#include "common/self_contact.h"
#include "common/self_contact_lists.h"
#include "common/task.h"

/* state: the carried state of common/self_contact_lists.h
 * (sc_block_decide, sc_decide_any); the refit does nothing in a substep where no block
 * makes its lists, and the walks only for the blocks that do (make). */
ATS_TASK void sc_leaf_boxes(int t, __global const float4* x, __global const int4* tris, __global float4* nodes,
                            __global const int* state) {
  if (state[1]) sc_leaf_box(t, x, (__global const int*)tris, nodes);
}

/* Node j of the level at `offset` from its children at `child_offset`. */
ATS_TASK void sc_refit_level(int j, __global float4* nodes, int offset, int child_offset, int children,
                             __global const int* state) {
  if (state[1]) sc_refit_node(nodes, offset + j, child_offset, 2 * j, children);
}

/* The levels from `from` to `root`, each after the one below (one work-item). */
ATS_TASK void sc_refit_top(int k, __global float4* nodes, __global const int* levels, int from, int root,
                           __global const int* state) {
  if (k == 0 && state[1]) sc_refit_levels(nodes, levels, from, root);
}

/* Per block of ATS_SC_BLOCK leaves the boxes of its corners at x_t, of
 * their displacements since x_det and of their predicted steps. */
ATS_TASK void sc_motion(int b, __global const float4* x_det, __global const float4* x_start,
                        __global const float4* x_guess, __global const int* corner_start, __global const int* corners,
                        __global float* motion) {
  sc_block_motion(b, x_det, x_start, x_guess, corner_start, corners, motion);
}

/* Cluster k's box at x_t, for the decision's first cut. */
ATS_TASK void sc_clusters(int k, __global const float* motion, int blocks, __global float* clusters) {
  sc_cluster_box(k, motion, blocks, clusters);
}

/* Whether block b makes its lists anew, and its rho (the task detect/decide_blocks). */
ATS_TASK void sc_decide_block(int b, __global const float* motion, __global const float* clusters, int blocks, float r,
                              float r_max, __global const float* rho0, __global float* rho, __global int* make) {
  sc_block_decide(b, motion, clusters, blocks, r, r_max, rho0, rho, make);
}

/* Whether any block does (one work-item; the task detect/decide_any). */
ATS_TASK void sc_decide_any_task(int k, __global const int* make, int blocks, float r_max, __global const float* rho,
                                 __global float* rho0, __global int* state) {
  if (k == 0) sc_decide_any(make, blocks, r_max, rho, rho0, state);
}

/* x_det = x_t where some block made its lists. */
ATS_TASK void sc_snap(int i, __global const float4* x_start, __global float4* x_det, __global const int* state) {
  if (state[1]) x_det[i] = x_start[i];
}

/* The lists of the leaves of group g, one walk per group
 * (common/self_contact_bvh.h sc_query_group), where its block makes them. */
ATS_TASK void sc_query_groups(int g, __global const float4* x, __global const int* inc, int n,
                              __global const int4* tris, __global const int2* edges, __global const int* leaves,
                              __global const float4* nodes, __global const int* levels, int root, int leaf_count,
                              __global const int* state, __global const int* make, __global int* vt, __global int* tv,
                              __global int* ee) {
  if (make[g * ATS_SC_GROUP / ATS_SC_BLOCK])
    sc_query_group(g, leaf_count, n, x, inc, (__global const int*)tris, (__global const int*)edges, leaves, nodes,
                   levels, root, as_float(state[2]), vt, tv, ee);
}

/* Once per substep, after the lists (common/self_contact_lists.h): every
 * listed pair's distance at x_t, per vertex, triangle and edge list; then
 * the bound (below) and the near lists the iterations and friction read. */
/* block: the block of each list's owner (a triangle's is t / ATS_SC_BLOCK);
 * radius: each block's rho, so a list's erosion is R_det - rho
 * (state[2]: R_det). listed: each list's count, packed, written in the
 * substep that made the list (make) and read by those that keep it
 * (sc_empty_reach). */
static inline int sc_list_empty(int id, int block, __global const int* list, __global const int* make,
                                __global int* listed) {
  if (make[block]) listed[id] = list[id * ATS_SC_STRIDE];
  return listed[id] == 0;
}
static inline float sc_eroded(int block, __global const int* state, __global const float* radius) {
  return as_float(state[2]) - radius[block];
}
ATS_TASK void sc_vertex_distances_task(int i, __global const float4* x, __global const int4* tris,
                                       __global const int* vt, __global const int* state, __global const int* block,
                                       __global const float* radius, __global const int* make, __global float* vt_d,
                                       __global float* vt_reach, __global int* listed) {
  const float eroded = sc_eroded(block[i], state, radius);
  if (sc_list_empty(i, block[i], vt, make, listed))
    vt_reach[i] = sc_empty_reach(as_float(state[2]), eroded);
  else
    sc_vertex_distances(i, x, (__global const int*)tris, vt, vt_d, eroded, vt_reach);
}
ATS_TASK void sc_triangle_distances_task(int t, __global const float4* x, __global const int4* tris,
                                         __global const int* tv, __global const int* state,
                                         __global const float* radius, __global const int* make, __global float* tv_d,
                                         __global float* tv_reach, __global int* listed) {
  const float eroded = sc_eroded(t / ATS_SC_BLOCK, state, radius);
  if (sc_list_empty(t, t / ATS_SC_BLOCK, tv, make, listed))
    tv_reach[t] = sc_empty_reach(as_float(state[2]), eroded);
  else
    sc_triangle_distances(t, x, (__global const int*)tris, tv, tv_d, eroded, tv_reach);
}
ATS_TASK void sc_edge_distances_task(int e, __global const float4* x, __global const int2* edges,
                                     __global const int* ee, __global const int* state, __global const int* block,
                                     __global const float* radius, __global const int* make, __global float* ee_d,
                                     __global float* ee_reach, __global int* listed) {
  const float eroded = sc_eroded(block[e], state, radius);
  if (sc_list_empty(e, block[e], ee, make, listed))
    ee_reach[e] = sc_empty_reach(as_float(state[2]), eroded);
  else
    sc_edge_distances(e, x, (__global const int*)edges, ee, ee_d, eroded, ee_reach);
}
/* The near lists (listed: as above): an empty list has an empty near list,
 * its count written (its horizon, [1], is read by nothing), and vertex
 * i's [1] the near entries it is in through its triangles and edges. */
ATS_TASK void sc_near_vertices(int i, __global const int* inc, int n, __global const int4* tris, __global const int* vt,
                               __global float* vt_d, __global const float* bound, float r, __global const int* tv_count,
                               __global const int* ee_count, __global const int* listed, __global int* vt_near,
                               __global int* vt_count, __global int* vt_total) {
  if (listed[i] == 0) {
    const int total = sc_near_through(i, inc, n, tv_count, ee_count);
    vt_near[i * ATS_SC_STRIDE] = 0;
    vt_near[i * ATS_SC_STRIDE + 1] = total;
    vt_count[i] = 0;
    vt_total[i] = total;
    return;
  }
  sc_near_vertex(i, inc, n, (__global const int*)tris, vt, vt_d, bound, r, tv_count, ee_count, vt_near, vt_count,
                 vt_total);
}
/* 1 when list id is empty, its near list then written empty. */
static inline int sc_near_none(int id, __global const int* listed, __global int* near, __global int* count) {
  if (listed[id] != 0) return 0;
  near[id * ATS_SC_STRIDE] = 0;
  count[id] = 0;
  return 1;
}
ATS_TASK void sc_near_triangles(int t, __global const int4* tris, __global const int* tv, __global float* tv_d,
                                __global const float* bound, float r, __global const int* listed, __global int* tv_near,
                                __global int* tv_count) {
  if (sc_near_none(t, listed, tv_near, tv_count)) return;
  sc_near_triangle(t, (__global const int*)tris, tv, tv_d, bound, r, tv_near, tv_count);
}
ATS_TASK void sc_near_edges(int e, __global const int2* edges, __global const int* ee, __global float* ee_d,
                            __global const float* bound, float r, __global const int* listed, __global int* ee_near,
                            __global int* ee_count) {
  if (sc_near_none(e, listed, ee_near, ee_count)) return;
  sc_near_edge(e, (__global const int*)edges, ee, ee_d, bound, r, ee_near, ee_count);
}

/* p held within distance b of q (VBD's truncation of a vertex's step). */
/* With surface contact on, a vertex step that ends deeper than
 * ATS_COLLIDER_SLACK of the thickness inside a collider's thickened surface
 * is put back to that depth: the surfaces' penalty pushing a layer into an
 * obstacle must not win over the obstacle (the collider penalty alone
 * shares the overlap with it: 6 % of the thickness). Not onto the surface
 * itself: a step to the surface kept VBD off the potential's minimum
 * (`converge` on two layers stalled near y = 0.1; with the slack it
 * reaches 1e-8). VBD's and JPGD's steps and SOSD's combine take it, and so do the clamps below; they
 * projected onto the surface after each iteration before (JPGD 0.28 ->
 * 0.033, SOSD 0.26 -> 0.10 on those layers, both rising between
 * doublings; now 2e-6 and 6.5e-4 at k = 256, docs/accuracy.md). */
#define ATS_COLLIDER_SLACK 0.005f
static inline float4 sc_out_of_colliders(float4 p, __global const ats_collider_c* colliders, int count,
                                         __global const ats_mesh_near* near, int on) {
  if (!on) return p;
  for (int c = 0; c < count; ++c) {
    if (ats_collider_clear(colliders + c, ats_v3(p.x, p.y, p.z))) continue;
    const ats_surface_distance s = ats_collider_gap_near(colliders + c, ats_v3(p.x, p.y, p.z), near);
    const float deepest = -ATS_COLLIDER_SLACK * colliders[c].thickness;
    if (s.phi < deepest) {
      const float push = deepest - s.phi;
      p = (float4)(p.x + push * s.n.x, p.y + push * s.n.y, p.z + push * s.n.z, p.w);
    }
  }
  return p;
}

/* Whether sc_apply (the friction's write-back) moved the vertex: only a move
 * it made can have taken it into a collider (the clamp and the colliders'
 * own tasks held it out before), and a mesh collider's distance is a tree
 * walk, too dear for every vertex when most have no pair to move them. */
static inline int sc_moved(float4 a, float4 b) { return a.x != b.x || a.y != b.y || a.z != b.z; }

static inline float4 sc_bounded(float4 p, float4 q, float b) {
  const float4 d = (float4)(p.x - q.x, p.y - q.y, p.z - q.z, 0.0f);
  /* well within the bound (1e-4 below its square, far above the rounding
   * of either side): p as the length would have kept it, without the root */
  if (d.x * d.x + d.y * d.y + d.z * d.z < 0.9999f * b * b) return p;
  const float len = length(d);
  if (!(len > b)) return p;
  const float s = b / len;
  return (float4)(q.x + s * d.x, q.y + s * d.y, q.z + s * d.z, p.w);
}

/* |a - b| over x, y, z: how far a vertex is from x_t (sc_still_apart). */
static inline float sc_distance_moved(float4 a, float4 b) {
  return length((float4)(a.x - b.x, a.y - b.y, a.z - b.z, 0.0f));
}

/* x[i] held within its bound of x_t, then out of the colliders: an obstacle
 * moving into the surface (a rising box) carries a vertex further than its
 * bound, which only limits how fast surfaces close on each other. */
static inline float4 sc_clamped(int i, __global const float4* x, __global const float4* x_start,
                                __global const float* bound, __global const ats_collider_c* colliders,
                                int collider_count, __global const ats_mesh_near* near) {
  return sc_out_of_colliders(sc_bounded(x[i], x_start[i], bound[i]), colliders, collider_count,
                             ats_near_of(colliders, collider_count, near, i), 1);
}
ATS_TASK void sc_clamp(int i, __global float4* x, __global const float4* x_start, __global const float* bound,
                       __global const ats_collider_c* colliders, int collider_count,
                       __global const ats_mesh_near* near) {
  x[i] = sc_clamped(i, x, x_start, bound, colliders, collider_count, near);
}

/* The step held within the bound, then how far the vertex is from x_t
 * (sc_moved_since) in the same pass: XPBD's, before its projection, which
 * reads both. Not out of the colliders: XPBD's iteration ends with its
 * collider task (it/collision/colliders) after the projection, which
 * would do it again (at 262K vertices 3.5 ms of a 95 ms substep). */
ATS_TASK void sc_clamp_moved(int i, __global float4* x, __global const float4* x_start, __global const float* bound,
                             __global float* moved) {
  const float4 a = sc_bounded(x[i], x_start[i], bound[i]);
  x[i] = a;
  moved[i] = sc_distance_moved(a, x_start[i]);
}

/* A pair's other vertices are read through SC_AT(j): x[j] here; VBD's solve
 * reads a vertex of its own colour from the iteration's start instead
 * (contact/self_contact_terms.h). */
#define SC_AT(j) x[j]

/* Every pair vertex i belongs to, with the pair's geometry g at x, its slot
 * in the pair and the four vertex ids pv[4]: as the point of a
 * vertex-triangle pair, as a corner of one, as an end of an edge-edge pair.
 * Reads the caller's i, x, tris, edges, inc, n and the near lists vt, tv and
 * ee (vt[i][1]: how many; none, nothing to read). */
#define SC_FOR_EACH_PAIR(BODY)                                                                                    \
  if (vt[(i)*ATS_SC_STRIDE + 1] > 0) {                                                                            \
    const float4 sc_p = x[i];                                                                                     \
    __global const int* sc_l = vt + (i)*ATS_SC_STRIDE;                                                            \
    for (int sc_m = 0; sc_m < sc_l[0]; ++sc_m) {                                                                  \
      const int4 sc_f = tris[sc_l[2 + sc_m]];                                                                     \
      const int pv[4] = {(i), sc_f.x, sc_f.y, sc_f.z};                                                            \
      const int slot = 0;                                                                                         \
      const ats_pair_geometry g =                                                                                 \
          ats_point_triangle(sc_v(sc_p), sc_v(SC_AT(sc_f.x)), sc_v(SC_AT(sc_f.y)), sc_v(SC_AT(sc_f.z)));          \
      BODY                                                                                                        \
    }                                                                                                             \
    for (int sc_k = inc[i]; sc_k < inc[(i) + 1]; ++sc_k) {                                                        \
      const int sc_t = inc[sc_k];                                                                                 \
      const int4 sc_f = tris[sc_t];                                                                               \
      const int slot = sc_f.x == (i) ? 1 : (sc_f.y == (i) ? 2 : 3);                                               \
      __global const int* sc_q = tv + sc_t * ATS_SC_STRIDE;                                                       \
      for (int sc_m = 0; sc_m < sc_q[0]; ++sc_m) {                                                                \
        const int sc_o = sc_q[2 + sc_m];                                                                          \
        const int pv[4] = {sc_o, sc_f.x, sc_f.y, sc_f.z};                                                         \
        const ats_pair_geometry g =                                                                               \
            ats_point_triangle(sc_v(SC_AT(sc_o)), sc_v(SC_AT(sc_f.x)), sc_v(SC_AT(sc_f.y)), sc_v(SC_AT(sc_f.z))); \
        BODY                                                                                                      \
      }                                                                                                           \
    }                                                                                                             \
    for (int sc_k = inc[(n) + 1 + (i)]; sc_k < inc[(n) + 2 + (i)]; ++sc_k) {                                      \
      const int sc_e = inc[sc_k];                                                                                 \
      const int2 sc_s = edges[sc_e];                                                                              \
      const int slot = sc_s.x == (i) ? 0 : 1;                                                                     \
      __global const int* sc_q = ee + sc_e * ATS_SC_STRIDE;                                                       \
      for (int sc_m = 0; sc_m < sc_q[0]; ++sc_m) {                                                                \
        const int2 sc_o2 = edges[sc_q[2 + sc_m]];                                                                 \
        const int pv[4] = {sc_s.x, sc_s.y, sc_o2.x, sc_o2.y};                                                     \
        const ats_pair_geometry g =                                                                               \
            ats_edge_edge(sc_v(SC_AT(sc_s.x)), sc_v(SC_AT(sc_s.y)), sc_v(SC_AT(sc_o2.x)), sc_v(SC_AT(sc_o2.y)));  \
        BODY                                                                                                      \
      }                                                                                                           \
    }                                                                                                             \
  }

/* VBD's conservative displacement bound of vertex i (§3.7), from the
 * distances above (common/self_contact_lists.h sc_vertex_bound). */
ATS_TASK void sc_bound(int i, __global const int* inc, int n, __global const float* vt_reach,
                       __global const float* tv_reach, __global const float* ee_reach, float gamma,
                       __global float* bound) {
  bound[i] = sc_vertex_bound(i, inc, n, vt_reach, tv_reach, ee_reach, gamma);
}

/* XPBD (Macklin et al. 2016) inequality constraint C = d - r >= 0 of every
 * listed pair, zero compliance: the pair's correction of its vertex in slot
 * j, -C w_j m_j n / sum_k m_k w_k^2 (m: inverse masses), summed over the
 * vertex's active pairs and divided by the number that count (sc_project;
 * Jacobi: every pair reads the same x). In two steps,
 * so that a pair's geometry is evaluated once per list that holds it rather
 * than once by each of its four vertices: per list entry (sc_pair_lambdas:
 * a vertex's triangles, a triangle's vertices, an edge's edges) the pair's
 * normal and multiplier lambda = -C / sum_k m_k w_k^2 and its weights, two
 * float4 (n, lambda; w), of the active pairs only, in list order from the
 * list's first slot, then an end mark (lambda < 0); then per vertex
 * (sc_project) the sum over the active entries, in the order of
 * SC_FOR_EACH_PAIR, written in place (the vertex reads only its own
 * position and the entries; most near pairs are inactive, and the gather
 * stops at the end mark instead of reading them). A pair both of whose sides list it (a vertex's
 * triangle that lists the vertex, two edges) is evaluated twice: reading the
 * one entry from the other side instead (a search of that side's list) made
 * the projection slower on the small dress (scratch measurement: 20 against
 * 12 ms per substep). */
/* How far vertex i is from x_t, the substep's start x0 (sc_still_apart). */
ATS_TASK void sc_moved_since(int i, __global const float4* x, __global const float4* x0, __global float* moved) {
  moved[i] = sc_distance_moved(x[i], x0[i]);
}

/* Whether the pair of near entry d0 (its distance at x_t) is still farther
 * than `reach` at x: a distance between a point and a triangle, or two
 * edges, moves by at most the largest displacement on each side (every
 * point of a side is a convex combination of its vertices), so
 * d(x) >= d0 - m_first - m_second, m the vertices' `moved`
 * (sc_moved_since). pv[0 .. split - 1] are the first side. The evaluations
 * below skip such a pair without its geometry: with reach 1 % beyond their
 * own test, the float geometry would have found it inactive too, so the
 * result is the same bit for bit. */
static inline int sc_still_apart(float d0, const int* pv, int split, __global const float* moved, float reach) {
  if (!(d0 > reach)) return 0;
  float m[2] = {0.0f, 0.0f};
  for (int j = 0; j < 4; ++j) m[j < split ? 0 : 1] = fmax(m[j < split ? 0 : 1], moved[pv[j]]);
  return d0 - m[0] - m[1] > reach;
}

/* Per block of ATS_SC_MOTION_BLOCK particles the largest `moved` of its
 * surface vertices, then (one work-item) of them all: every pair's vertices
 * are surface vertices, so no side of any pair moved farther. */
ATS_TASK void sc_moved_blocks(int b, __global const float* moved, __global const int* inc, int n,
                              __global float* block_max) {
  const int end = (b + 1) * ATS_SC_MOTION_BLOCK < n ? (b + 1) * ATS_SC_MOTION_BLOCK : n;
  float m = 0.0f;
  for (int i = b * ATS_SC_MOTION_BLOCK; i < end; ++i)
    if (sc_is_surface(inc, i)) m = fmax(m, moved[i]);
  block_max[b] = m;
}
ATS_TASK void sc_moved_max(int k, __global const float* block_max, int blocks, __global float* most) {
  if (k != 0) return;
  float m = 0.0f;
  for (int b = 0; b < blocks; ++b) m = fmax(m, block_max[b]);
  most[0] = m;
}

static inline int sc_store_lambda(ats_pair_geometry g, const int* pv, __global const float4* x, float r,
                                  __global float4* out) {
  float denom = 0.0f;
  if (g.d < r && g.d > 1e-12f)
    for (int j = 0; j < 4; ++j) denom += x[pv[j]].w * g.w[j] * g.w[j];
  if (!(denom > 0.0f)) return 0;
  const ats_vec3 nrm = ats_pair_normal(g);
  out[0] = (float4)(nrm.x, nrm.y, nrm.z, (r - g.d) / denom);
  out[1] = (float4)(g.w[0], g.w[1], g.w[2], g.w[3]);
  return 1;
}

/* After a list's active entries (written in list order from its first
 * slot): an end mark, lambda < 0, unless every entry is active. */
static inline void sc_end_lambdas(int active, int count, __global float4* out) {
  if (active < count) out[2 * active] = (float4)(0.0f, 0.0f, 0.0f, -1.0f);
}
/* List id of `count` near entries, none evaluated (none near, or all apart). */
static inline void sc_no_lambdas(int id, int count, __global float4* out, __global int* active) {
  sc_end_lambdas(0, count, out);
  active[id] = 0;
}

/* The entries of vertex i's list (as the point of a vertex-triangle pair). */
/* count: the lists' near counts, packed (common/self_contact_lists.h
 * sc_near_vertex): most lists have none, and their pass reads no list. */
ATS_TASK void sc_pair_lambdas_points(int i, __global const float4* x, __global const float* moved,
                                     __global const float* most, __global const int4* tris, __global const int* vt,
                                     __global const float* vt_d, __global const int* count, float r,
                                     __global float4* out, __global int* active) {
  __global const float* d0 = vt_d + i * ATS_SC_STRIDE;
  __global float4* o = out + 2 * i * ATS_SC_CAPACITY;
  if (count[i] == 0 || sc_list_apart(d0[0], moved[i], most[0], 1.01f * r)) {
    sc_no_lambdas(i, count[i], o, active);
    return;
  }
  __global const int* l = vt + i * ATS_SC_STRIDE;
  const ats_vec3 p = sc_v(x[i]);
  int k = 0;
  for (int m = 0; m < l[0]; ++m) {
    const int4 f = tris[l[2 + m]];
    const int pv[4] = {i, f.x, f.y, f.z};
    if (sc_still_apart(d0[2 + m], pv, 1, moved, 1.01f * r)) continue;
    k += sc_store_lambda(ats_point_triangle(p, sc_v(x[f.x]), sc_v(x[f.y]), sc_v(x[f.z])), pv, x, r, o + 2 * k);
  }
  sc_end_lambdas(k, l[0], o);
  active[i] = k;
}

/* The entries of triangle t's list (the points near it). */
ATS_TASK void sc_pair_lambdas_triangles(int t, __global const float4* x, __global const float* moved,
                                        __global const float* most, __global const int4* tris, __global const int* tv,
                                        __global const float* tv_d, __global const int* count, float r,
                                        __global float4* out, __global int* active) {
  __global const float* d0 = tv_d + t * ATS_SC_STRIDE;
  __global float4* o = out + 2 * t * ATS_SC_CAPACITY;
  if (count[t] == 0) {  // most lists: not even the triangle read
    sc_no_lambdas(t, 0, o, active);
    return;
  }
  const int4 f = tris[t];
  if (sc_list_apart(d0[0], most[0], sc_side_bound(moved, f.x, f.y, f.z), 1.01f * r)) {
    sc_no_lambdas(t, count[t], o, active);
    return;
  }
  __global const int* l = tv + t * ATS_SC_STRIDE;
  const ats_vec3 a = sc_v(x[f.x]), b = sc_v(x[f.y]), c = sc_v(x[f.z]);
  int k = 0;
  for (int m = 0; m < l[0]; ++m) {
    const int v = l[2 + m];
    const int pv[4] = {v, f.x, f.y, f.z};
    if (sc_still_apart(d0[2 + m], pv, 1, moved, 1.01f * r)) continue;
    k += sc_store_lambda(ats_point_triangle(sc_v(x[v]), a, b, c), pv, x, r, o + 2 * k);
  }
  sc_end_lambdas(k, l[0], o);
  active[t] = k;
}

/* The entries of edge e's list (the edges near it). */
ATS_TASK void sc_pair_lambdas_edges(int e, __global const float4* x, __global const float* moved,
                                    __global const float* most, __global const int2* edges, __global const int* ee,
                                    __global const float* ee_d, __global const int* count, float r,
                                    __global float4* out, __global int* active) {
  __global const float* d0 = ee_d + e * ATS_SC_STRIDE;
  __global float4* o = out + 2 * e * ATS_SC_CAPACITY;
  if (count[e] == 0) {  // most lists: not even the edge read
    sc_no_lambdas(e, 0, o, active);
    return;
  }
  const int2 s = edges[e];
  if (sc_list_apart(d0[0], sc_side_bound(moved, s.x, s.y, -1), most[0], 1.01f * r)) {
    sc_no_lambdas(e, count[e], o, active);
    return;
  }
  __global const int* l = ee + e * ATS_SC_STRIDE;
  const ats_vec3 a = sc_v(x[s.x]), b = sc_v(x[s.y]);
  int k = 0;
  for (int m = 0; m < l[0]; ++m) {
    const int2 h = edges[l[2 + m]];
    const int pv[4] = {s.x, s.y, h.x, h.y};
    if (sc_still_apart(d0[2 + m], pv, 2, moved, 1.01f * r)) continue;
    k += sc_store_lambda(ats_edge_edge(a, b, sc_v(x[h.x]), sc_v(x[h.y])), pv, x, r, o + 2 * k);
  }
  sc_end_lambdas(k, l[0], o);
  active[e] = k;
}

/* The corrections of a list's active entries (up to its end mark) to the
 * vertex in `slot` with inverse mass w, added to *sum, their lengths to
 * *mag and the longest into *most. */
static inline void sc_add_corrections(__global const float4* e, int count, int slot, float w, ats_vec3* sum, float* mag,
                                      float* most) {
  for (int m = 0; m < count; ++m, e += 2) {
    const float4 nl = e[0];
    if (nl.w < 0.0f) break;
    const float4 ws = e[1];
    const float ws_slot = slot == 0 ? ws.x : (slot == 1 ? ws.y : (slot == 2 ? ws.z : ws.w));
    const float c = nl.w * w * ws_slot;
    *sum = ats_add(*sum, ats_scale(ats_v3(nl.x, nl.y, nl.z), c));
    *mag += fabs(c);
    *most = fmax(*most, fabs(c));
  }
}

/* vt_k, tv_k, ee_k: per list the count of its active entries (the
 * sc_pair_lambdas_* of this iteration), read densely so that a list with
 * none is never opened. */
ATS_TASK void sc_project(int i, __global float4* x, __global const int4* tris, __global const int2* edges,
                         __global const int* inc, int n, __global const int* vt_total, __global const float4* vt_l,
                         __global const float4* tv_l, __global const float4* ee_l, __global const int* vt_k,
                         __global const int* tv_k, __global const int* ee_k) {
  if (!(vt_total[i] > 0)) return;
  const float4 p = x[i];
  if (p.w == 0.0f || !sc_is_surface(inc, i)) return;
  ats_vec3 sum = ats_v3(0, 0, 0);
  float mag = 0.0f, most = 0.0f;
  if (vt_k[i] > 0) sc_add_corrections(vt_l + 2 * i * ATS_SC_CAPACITY, vt_k[i], 0, p.w, &sum, &mag, &most);
  for (int k = inc[i]; k < inc[i + 1]; ++k) {
    const int t = inc[k];
    if (tv_k[t] == 0) continue;
    const int4 f = tris[t];
    const int slot = f.x == i ? 1 : (f.y == i ? 2 : 3);
    sc_add_corrections(tv_l + 2 * t * ATS_SC_CAPACITY, tv_k[t], slot, p.w, &sum, &mag, &most);
  }
  for (int k = inc[n + 1 + i]; k < inc[n + 2 + i]; ++k) {
    const int e = inc[k];
    if (ee_k[e] == 0) continue;
    const int slot = edges[e].x == i ? 0 : 1;
    sc_add_corrections(ee_l + 2 * e * ATS_SC_CAPACITY, ee_k[e], slot, p.w, &sum, &mag, &most);
  }
  if (!(most > 0.0f)) return;  // no active pair, or none that moves i
  // The sum over the number of corrections that count: their lengths over
  // the longest (equal corrections: their count, as a plain average; one
  // deep pair among near-satisfied ones: about 1). A plain average let a
  // vertex in many pairs barely move: a pillows_small cloth vertex pressed
  // over a pillow's edge had 24-55 active corrections, summing to 42 mm and
  // moving 1.7 mm an iteration, and stayed 3.15 mm from the pillow (thickness
  // 10 mm) for six frames. The step is never longer than the longest
  // correction (|sum| <= mag).
  const float s = 1.0f / fmax(1.0f, mag / most);
  x[i] = (float4)(p.x + s * sum.x, p.y + s * sum.y, p.z + s * sum.z, p.w);
}

/* Friction between the surfaces: its own file. */
#include "contact/self_contact_friction.cl"
