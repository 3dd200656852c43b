/* The surface contact energy (common/self_contact.h) in a vertex's force and
 * Hessian block, for the vertex-block methods (VBD, JPGD, SOSD): every pair
 * the detection found for vertex i (contact/self_contact.cl), evaluated at
 * the current positions x, as in VBD (Chen et al. 2024 §3.7). Include after
 * common/vertex_system.cl and contact/self_contact.cl. */
#ifndef ATS_SELF_CONTACT_TERMS_H
#define ATS_SELF_CONTACT_TERMS_H

/* A pair's Hessian block of vertex i in its solve: k w_i^2 n n^T, times
 * SC_SPREAD (1 but in SOSD's, below). */
#define SC_VERTEX_TERMS_BODY                                                                        \
  if (!on || x[i].w == 0.0f || !sc_is_surface(inc, i)) return s;                                    \
  SC_FOR_EACH_PAIR({                                                                                \
    if (g.d < r) {                                                                                  \
      s.f = ats_sub(s.f, ats_pair_gradient(g, k, r, slot));                                         \
      s.h = ats_m3_add(s.h, ats_m3_scale(ats_pair_hessian(g, k, r, slot, slot), SC_SPREAD(g, pv))); \
    }                                                                                               \
  })                                                                                                \
  return s;
#define SC_SPREAD(g, pv) 1.0f

/* Jacobi methods (SOSD, JPGD): every vertex reads the same x. */
static inline vertex_system add_self_contact_terms(vertex_system s, int i, __global const float4* x,
                                                   __global const int4* tris, __global const int2* edges,
                                                   __global const int* inc, int n, __global const int* vt,
                                                   __global const int* tv, __global const int* ee, float k, float r,
                                                   int on) {
  SC_VERTEX_TERMS_BODY
}

/* SOSD: every free vertex of a pair steps at once, each with the pair's
 * block k w_i^2 closing nearly the whole gap, and SOSD's combine has no
 * step length to share it out (JPGD's 0.5 does): the gap overshot, and
 * `converge` on two layers rose between doublings (0.11 at k = 32, 0.13 at
 * 64). With the block spread over the pair, k |w_i| sum_j |w_j| (the
 * row sum of the pair's k w w^T over its free vertices, Gershgorin), the
 * vertices' shares add up to at most the gap: y falls at every doubling
 * (0.23 -> 6.5e-4 at k = 256). The gradient, so the minimum, is the same. */
static inline float sc_spread(ats_pair_geometry g, const int* pv, int slot, __global const float4* x) {
  float sum = 0.0f;
  for (int j = 0; j < 4; ++j) sum += x[pv[j]].w > 0.0f ? fabs(g.w[j]) : 0.0f;
  return fabs(g.w[slot]) > 0.0f ? fmax(1.0f, sum / fabs(g.w[slot])) : 1.0f;
}
#undef SC_SPREAD
#define SC_SPREAD(g, pv) sc_spread(g, pv, slot, x)
static inline vertex_system add_self_contact_terms_spread(vertex_system s, int i, __global const float4* x,
                                                          __global const int4* tris, __global const int2* edges,
                                                          __global const int* inc, int n, __global const int* vt,
                                                          __global const int* tv, __global const int* ee, float k,
                                                          float r, int on) {
  SC_VERTEX_TERMS_BODY
}
#undef SC_SPREAD
#define SC_SPREAD(g, pv) 1.0f

/* Gauss-Seidel over colours (VBD): a contact pair can join two vertices of
 * one colour, which are solved at the same time (on two work-groups or two
 * devices), so the one would read the other while it is written. A partner
 * of vertex i's own colour is read from x_iter, the positions at the
 * iteration's start, which is where it stands until its colour's solve;
 * partners of other colours from x. The result no longer depends on how the
 * colour's vertices are shared out (before: two runs of one scene on the
 * 2-CU device ended 8 cm apart after 20 frames). */
#undef SC_AT
#define SC_AT(j) (color[j] == color[i] ? x_iter[j] : x[j])
static inline vertex_system add_self_contact_terms_gs(vertex_system s, int i, __global const float4* x,
                                                      __global const float4* x_iter, __global const int* color,
                                                      __global const int4* tris, __global const int2* edges,
                                                      __global const int* inc, int n, __global const int* vt,
                                                      __global const int* tv, __global const int* ee, float k, float r,
                                                      int on) {
  SC_VERTEX_TERMS_BODY
}
#undef SC_AT
#define SC_AT(j) x[j]
#undef SC_SPREAD
#undef SC_VERTEX_TERMS_BODY

/* A Newton step taken with the pairs active at x (d < r) ignores a pair
 * that the step itself brings within r: a vertex just outside the
 * thickness dived through it (5.7e-5 m, 500x the penalty's equilibrium
 * depth, on a patch resting on a tilted cloth), was pushed out by the next
 * iteration and in again by the one after; the substep ended at either,
 * and the surfaces' normal jitter (up to 2 mm under VBD) overstated the
 * load that friction scales. So the step is redone with every pair that
 * its end point would press -- with the pair's distance linearised in the
 * vertex's step, d + w n . dx, the contact energy is a convex piecewise
 * quadratic of dx, and the pairs active at the step's end are its active
 * set -- until the set stops changing (three passes at most). `system`:
 * the vertex's force and Hessian with the pairs active at x; `ahead`
 * evaluates the pairs inactive at x at the step dx. */
#define SC_AHEAD_BODY                                                  \
  int s_added = 0;                                                     \
  SC_FOR_EACH_PAIR({                                                   \
    if (!(g.d < r)) {                                                  \
      const ats_vec3 nrm = ats_pair_normal(g);                         \
      if (r - g.d - g.w[slot] * ats_dot(nrm, dx) > 0.0f) {             \
        s.f = ats_add(s.f, ats_scale(nrm, k * (r - g.d) * g.w[slot])); \
        s.h = ats_m3_add(s.h, ats_pair_hessian_any(g, k, slot));       \
        ++s_added;                                                     \
      }                                                                \
    }                                                                  \
  })                                                                   \
  *added = s_added;                                                    \
  return s;

/* k w^2 n n^T whether or not the pair is within r (ats_pair_hessian's
 * block, for a pair the step brings within r). */
static inline ats_mat3 ats_pair_hessian_any(ats_pair_geometry g, float k, int j) {
  const ats_vec3 n = ats_pair_normal(g);
  return ats_m3_scale(ats_m3_outer(n, n), k * g.w[j] * g.w[j]);
}

static inline vertex_system sc_ahead(vertex_system s, int* added, ats_vec3 dx, int i, __global const float4* x,
                                     __global const int4* tris, __global const int2* edges, __global const int* inc,
                                     int n, __global const int* vt, __global const int* tv, __global const int* ee,
                                     float k, float r) {
  SC_AHEAD_BODY
}

#undef SC_AT
#define SC_AT(j) (color[j] == color[i] ? x_iter[j] : x[j])
static inline vertex_system sc_ahead_gs(vertex_system s, int* added, ats_vec3 dx, int i, __global const float4* x,
                                        __global const float4* x_iter, __global const int* color,
                                        __global const int4* tris, __global const int2* edges, __global const int* inc,
                                        int n, __global const int* vt, __global const int* tv, __global const int* ee,
                                        float k, float r) {
  SC_AHEAD_BODY
}
#undef SC_AT
#define SC_AT(j) x[j]
#undef SC_AHEAD_BODY

/* The vertex step H^-1 f of `system`, redone with the pairs the step
 * brings within r (above). x_iter, color: VBD's (null: Jacobi). */
static inline ats_solve3 sc_contact_step(vertex_system system, int i, __global const float4* x,
                                         __global const float4* x_iter, __global const int* color,
                                         __global const int4* tris, __global const int2* edges, __global const int* inc,
                                         int n, __global const int* vt, __global const int* tv, __global const int* ee,
                                         float k, float r, int on) {
  ats_solve3 d = ats_m3_solve(system.h, system.f);
  if (!on || !d.ok || x[i].w == 0.0f || !sc_is_surface(inc, i)) return d;
  int last = 0;
  for (int pass = 0; pass < 3; ++pass) {
    int added = 0;
    const vertex_system ahead =
        color ? sc_ahead_gs(system, &added, d.x, i, x, x_iter, color, tris, edges, inc, n, vt, tv, ee, k, r)
              : sc_ahead(system, &added, d.x, i, x, tris, edges, inc, n, vt, tv, ee, k, r);
    if (added == last && pass > 0) break;
    last = added;
    if (added == 0) break;
    const ats_solve3 e = ats_m3_solve(ahead.h, ahead.f);
    if (!e.ok) break;
    d = e;
  }
  return d;
}

/* The new position of vertex i held within its bound of x_t. */
static inline float4 sc_bounded_step(float4 next, int i, __global const float4* x_start, __global const float* bound,
                                     int on) {
  return on ? sc_bounded(next, x_start[i], bound[i]) : next;
}

#endif
