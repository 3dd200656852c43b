/* Contact between simulated surfaces (scene `contact: {self: true}`):
 * collision detection at the start of every substep, on x_t (Chen et al.
 * 2024, VBD §3.7), as tasks that range over independent elements:
 *   sc_leaf_boxes, sc_refit_level, sc_refit_top: refit the BVH over the
 *     surface triangles (built once on the host, solver/layout/
 *     self_contact_layout), one task per level up to the small top levels;
 *   sc_query_leaves: per vertex the triangles, per triangle the vertices and
 *     per edge the edges within the query radius (incident pairs excluded),
 *     the ATS_SC_CAPACITY nearest of each, and the nearest distance, in one
 *     walk per leaf for the primitives it owns;
 *   sc_bound: per vertex the conservative displacement bound of VBD:
 *     gamma times the distance to the nearest primitive it could meet
 *     (as a point, through its triangles, through its edges), so that no
 *     vertex passes through a triangle within the substep;
 *   sc_clamp: a position held within its bound of x_t (the first guess;
 *     every solve step of the vertex methods does the same);
 *   sc_project, sc_apply: XPBD's inequality constraints d >= r of every pair
 *     of a vertex, Jacobi-averaged, into a scratch copy and back (bounded);
 *   sc_friction (then sc_apply): Coulomb friction between the surfaces,
 *     after the iterations, every method.
 * The pair lists: per primitive ATS_SC_STRIDE ints, [count, nearest distance
 * (float bits), ids of the nearest first]. */
#include "common/ats_math.h"
#include "common/self_contact.h"
#include "common/self_contact_bvh.h"
#include "common/task.h"

/* state: the frame_state of common/self_contact_bvh.h (sc_decide); the
 * detection tasks do nothing in a substep that keeps the lists. */
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

/* Per block of ATS_SC_MOTION_BLOCK particles the largest displacement since
 * the lists were made and the largest predicted step. */
ATS_TASK void sc_motion(int b, __global const float4* x_det, __global const float4* x_start,
                        __global const float4* x_guess, __global const int* inc, int n, __global float* block_max) {
  sc_block_motion(b, x_det, x_start, x_guess, inc, n, block_max);
}

/* Whether this substep rebuilds the lists (one work-item). */
ATS_TASK void sc_decide_detection(int k, __global const float* block_max, int blocks, float r, float r_max,
                                  __global int* state) {
  if (k == 0) sc_decide(block_max, blocks, r, r_max, state);
}

/* x_det: where the lists are made. */
ATS_TASK void sc_snap(int i, __global const float4* x_start, __global float4* x_det, __global const int* state) {
  if (state[1]) x_det[i] = x_start[i];
}

/* The three queries of leaf u in one walk (common/self_contact_bvh.h). */
ATS_TASK void sc_query_leaves(int u, __global const float4* x, __global const int* inc, __global const int4* tris,
                              __global const int2* edges, __global const int* leaves, __global const float4* nodes,
                              __global const int* levels, int root, __global const int* state, __global int* vt,
                              __global int* tv, __global int* ee) {
  if (state[1])
    sc_query_leaf(u, x, inc, (__global const int*)tris, (__global const int*)edges, leaves, nodes, levels, root,
                  as_float(state[2]), vt, tv, ee);
}

/* p held within distance b of q (VBD's truncation of a vertex's step). */
static inline float4 sc_bounded(float4 p, float4 q, float b) {
  const float4 d = (float4)(p.x - q.x, p.y - q.y, p.z - q.z, 0.0f);
  const float len = length(d);
  if (!(len > b)) return p;
  const float s = b / len;
  return (float4)(q.x + s * d.x, q.y + s * d.y, q.z + s * d.z, p.w);
}

ATS_TASK void sc_clamp(int i, __global float4* x, __global const float4* x_start, __global const float* bound) {
  x[i] = sc_bounded(x[i], x_start[i], bound[i]);
}

/* A pair's other vertices are read through SC_AT(j): x[j] here; VBD's solve
 * reads a vertex of its own colour from the iteration's start instead
 * (contact/self_contact_terms.h). */
#define SC_AT(j) x[j]

/* Every pair vertex i belongs to, with the pair's geometry g at x, its slot
 * in the pair and the four vertex ids pv[4]: as the point of a
 * vertex-triangle pair, as a corner of one, as an end of an edge-edge pair.
 * Reads the caller's i, x, tris, edges, inc, n, vt, tv and ee. */
#define SC_FOR_EACH_PAIR(BODY)                                                                                    \
  {                                                                                                               \
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

/* VBD's conservative displacement bound of vertex i (§3.7): gamma times
 * the distance to the nearest primitive it could meet, on x_t: its listed
 * pairs' distances now, and what its lists' horizons leave for the rest
 * (common/self_contact_bvh.h sc_unlisted_distance). */
ATS_TASK void sc_bound(int i, __global const float4* x, __global const int4* tris, __global const int2* edges,
                       __global const int* inc, int n, __global const int* vt, __global const int* tv,
                       __global const int* ee, __global const int* state, float gamma, __global float* bound) {
  if (!sc_is_surface(inc, i)) {
    bound[i] = 1e30f;
    return;
  }
  float d = sc_unlisted_distance(i, inc, n, vt, tv, ee, as_float(state[3]));
  SC_FOR_EACH_PAIR({ d = fmin(d, g.d); })
  bound[i] = gamma * fmax(d, 0.0f);
}

/* XPBD (Macklin et al. 2016) inequality constraint C = d - r >= 0 of every
 * pair of vertex i, zero compliance: the pair's correction of vertex i,
 * -C w_i m_i n / sum_j m_j w_j^2 (m: inverse masses), averaged over its
 * active pairs (Jacobi; every vertex reads the same x). */
ATS_TASK void sc_project(int i, __global const float4* x, __global float4* x_out, __global const int4* tris,
                         __global const int2* edges, __global const int* inc, int n, __global const int* vt,
                         __global const int* tv, __global const int* ee, float r) {
  const float4 p = x[i];
  x_out[i] = p;
  if (p.w == 0.0f || !sc_is_surface(inc, i)) return;
  ats_vec3 sum = ats_v3(0, 0, 0);
  int active = 0;
  SC_FOR_EACH_PAIR({
    if (g.d < r && g.d > 1e-12f) {
      float denom = 0.0f;
      for (int j = 0; j < 4; ++j) denom += x[pv[j]].w * g.w[j] * g.w[j];
      if (denom > 0.0f) {
        const float lambda = (r - g.d) / denom;
        sum = ats_add(sum, ats_scale(ats_pair_normal(g), lambda * p.w * g.w[slot]));
        ++active;
      }
    }
  })
  if (active == 0) return;
  const float s = 1.0f / (float)active;
  x_out[i] = (float4)(p.x + s * sum.x, p.y + s * sum.y, p.z + s * sum.z, p.w);
}

ATS_TASK void sc_apply(int i, __global float4* x, __global const float4* x_out, __global const float4* x_start,
                       __global const float* bound) {
  x[i] = sc_bounded(x_out[i], x_start[i], bound[i]);
}

/* Coulomb friction of every pair of vertex i in contact (d < 1.01 r), after
 * the iterations. A pair has two sides, the point and the triangle, or the
 * two edges (weights w_j > 0 and < 0); its relative displacement over the
 * substep is u = sum_j w_j (x_j - x_prev_j), the motion of the first side's
 * point against the second's. Its tangential part is removed whole when it
 * is within mu_s dn (static), else by mu_k dn (kinetic), dn the normal
 * displacement the contact made against the inertial prediction
 * x~ = x_prev + h v (v already holds the substep's gravity),
 * dn = n . sum_j w_j (x_j - x~_j). Each side takes the share of the other
 * side's inverse mass (sum of w_j^2 / m_j over the side), and every vertex of
 * a side moves by its side's share, so that the pair's relative motion loses
 * what Coulomb removes. Vertex i averages its pairs weighted by how hard they
 * press (dn); into x_out (Jacobi). */
/* The coefficients of one side of a pair: its material's (pf, -1: unset),
 * else the scene's contact.friction (mu). A pair takes the mean of its sides. */
static inline float2 sc_side_mu(float2 pf, float2 mu) { return pf.x < 0.0f ? mu : pf; }

ATS_TASK void sc_friction(int i, __global const float4* x, __global float4* x_out, __global const float4* x_prev,
                          __global const float4* v, float h, __global const int4* tris, __global const int2* edges,
                          __global const int* inc, int n, __global const int* vt, __global const int* tv,
                          __global const int* ee, float r, float mu_s, float mu_k, __global const float2* pf) {
  const float4 p = x[i];
  x_out[i] = p;
  if (p.w == 0.0f || !sc_is_surface(inc, i)) return;
  /* Touching: XPBD's projection leaves its pairs at d = r exactly. */
  const float touching = 1.01f * r;
  ats_vec3 sum = ats_v3(0, 0, 0);
  float weight = 0.0f;
  SC_FOR_EACH_PAIR({
    if (g.d < touching && g.d > 1e-12f && g.w[slot] != 0.0f) {
      const ats_vec3 nrm = ats_pair_normal(g);
      /* (no comma outside parentheses: the body is a macro argument) */
      ats_vec3 u = ats_v3(0, 0, 0);
      ats_vec3 push = ats_v3(0, 0, 0);
      float first = 0.0f;
      float second = 0.0f;
      float2 mu_first = (float2)(0.0f);
      float2 mu_second = (float2)(0.0f);
      for (int j = 0; j < 4; ++j) {
        const float4 xj = x[pv[j]];
        const float4 qj = x_prev[pv[j]];
        const float4 vj = v[pv[j]];
        u = ats_add(u, ats_scale(ats_v3(xj.x - qj.x, xj.y - qj.y, xj.z - qj.z), g.w[j]));
        push = ats_add(
            push, ats_scale(ats_v3(xj.x - qj.x - h * vj.x, xj.y - qj.y - h * vj.y, xj.z - qj.z - h * vj.z), g.w[j]));
        if (g.w[j] > 0.0f) first += g.w[j] * g.w[j] * xj.w;
        if (g.w[j] < 0.0f) second += g.w[j] * g.w[j] * xj.w;
        if (g.w[j] > 0.0f) mu_first = sc_side_mu(pf[pv[j]], (float2)(mu_s, mu_k));
        if (g.w[j] < 0.0f) mu_second = sc_side_mu(pf[pv[j]], (float2)(mu_s, mu_k));
      }
      const float dn = ats_dot(push, nrm);
      const ats_vec3 ut = ats_sub(u, ats_scale(nrm, ats_dot(u, nrm)));
      const float len = ats_length(ut);
      if (dn > 0.0f && len > 0.0f && first + second > 0.0f) {
        const float2 mu = 0.5f * (mu_first + mu_second);
        const float removed = len <= mu.x * dn ? 1.0f : fmin(1.0f, mu.y * dn / len);
        /* On the first side i moves against u, on the second with it. */
        const float share = g.w[slot] > 0.0f ? -first / (first + second) : second / (first + second);
        sum = ats_add(sum, ats_scale(ut, dn * removed * share));
        weight += dn;
      }
    }
  })
  if (!(weight > 0.0f)) return;
  const float s = 1.0f / weight;
  x_out[i] = (float4)(p.x + s * sum.x, p.y + s * sum.y, p.z + s * sum.z, p.w);
}
