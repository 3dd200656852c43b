/* Block-Jacobi preconditioned gradient descent with Chebyshev acceleration
 * (Wang & Yang 2016; Wang 2015): every vertex at once takes the step
 * alpha H_ii^-1 f_i from x^k, then x^{k+1} = omega (x^k + step - x^{k-1}) + x^{k-1}
 * + beta (x^k - x^{k-1}): Chebyshev weights omega (beta = 0), or heavy-ball
 * momentum beta (omega = 1).
 * A full Jacobi step (alpha = 1) overshoots where stiff neighbours pull on
 * the same vertex, so alpha < 1 (default 0.5) keeps it a descent step.
 * Reads x^k and x^{k-1}, writes x^{k+1}: no vertex sees another's update of
 * the same iteration, so any cut between devices computes the same result. */
#pragma OPENCL FP_CONTRACT OFF /* the stretch energy's error-free transforms */

#include "common/ats_math.h"
#include "common/vertex_solve.h"
#include "common/vertex_system.cl"
#include "common/vertex_system_lanes.h"
#include "common/vertex_contact.h"
#include "contact/self_contact.cl"
#include "contact/self_contact_terms.h"
#include "common/contact_steps.cl"
#include "common/vertex_friction.cl"
#include "common/particle_steps.cl"
#include "async/merge.cl"

/* Vertex p's next iterate from its system s and its solve d: alpha of the
 * way, the ground, and the acceleration from its previous iterate. */
static inline float4 jpgd_next(float4 p, vertex_system s, ats_solve3 d, float4 p_before, float alpha, float omega,
                               float beta, int has_ground, float ground) {
  ats_vec3 step = ats_scale(d.x, alpha);
  if (d.ok && has_ground && p.y + step.y < ground) {
    step = ats_scale(ats_vertex_step_above_ground(s.h, s.f, d.x, p.y, ground), alpha);
    step.y = ground - p.y; /* the bound itself, not alpha of the way to it */
  }
  const float3 stepped = (float3)(p.x + step.x, p.y + step.y, p.z + step.z);
  const float3 before = p_before.xyz;
  return (float4)(omega * (stepped - before) + before + beta * ((float3)(p.x, p.y, p.z) - before), p.w);
}

/* Vertex i's step from its gathered system g: spring damping, collider and
 * surface contact terms, the 3x3 solve, alpha of the way, the ground and the
 * acceleration. */
static inline void jpgd_vertex(int i, vertex_system g, __global const float4* x, __global const float4* x_before,
                               __global float4* x_next, __global const int* adj_offsets, __global const int* adj,
                               __global const ats_distance_c* stretch, float inv_h2, float alpha, float omega,
                               float beta, int has_ground, float ground, __global const ats_collider_c* colliders,
                               int collider_count, __global const ats_mesh_near* near, __global const float4* x_start,
                               float inv_h, __global const int4* sc_tris, __global const int2* sc_edges,
                               __global const int* sc_inc, __global const int* sc_vt, __global const int* sc_tv,
                               __global const int* sc_ee, int sc_n, float sc_k, float sc_r, int sc_on) {
  const float4 p = x[i];
  if (p.w == 0.0f) {
    x_next[i] = p;
    return;
  }
  __global const ats_mesh_near* mine = ats_near_of(colliders, collider_count, near, i);
  const vertex_system s =
      add_self_contact_terms(add_contact_terms(add_spring_damping(g, i, x, x_start, inv_h, adj_offsets, adj, stretch),
                                               vs_xyz(p), p.w, inv_h2, colliders, collider_count, mine),
                             i, x, sc_tris, sc_edges, sc_inc, sc_n, sc_vt, sc_tv, sc_ee, sc_k, sc_r, sc_on);
  const ats_solve3 d =
      sc_contact_step(s, i, x, 0, 0, sc_tris, sc_edges, sc_inc, sc_n, sc_vt, sc_tv, sc_ee, sc_k, sc_r, sc_on);
  x_next[i] = sc_out_of_colliders(jpgd_next(p, s, d, x_before[i], alpha, omega, beta, has_ground, ground), colliders,
                                  collider_count, mine, sc_on);
}

#define JPGD_TAIL_ARGS                                                                                       \
  x, x_before, x_next, adj_offsets, adj, stretch, inv_h2, alpha, omega, beta, has_ground, ground, colliders, \
      collider_count, near, x_start, inv_h, sc_tris, sc_edges, sc_inc, sc_vt, sc_tv, sc_ee, sc_n, sc_k, sc_r, sc_on

/* solver.ordering: vertices. A pinned vertex skips its gather. */
ATS_TASK void jpgd_step(int i, __global const float4* x, __global const float4* x_before, __global float4* x_next,
                        __global const float4* x_tilde, __global const int* adj_offsets, __global const int* adj,
                        __global const ats_distance_c* stretch, __global const ats_bend_c* bend,
                        __global const ats_tet_c* tets, float inv_h2, float alpha, float omega, float beta,
                        int has_ground, float ground, __global const ats_collider_c* colliders, int collider_count,
                        __global const ats_mesh_near* near, __global const float4* x_start, float inv_h,
                        __global const int4* sc_tris, __global const int2* sc_edges, __global const int* sc_inc,
                        __global const int* sc_vt, __global const int* sc_tv, __global const int* sc_ee,
                        __global const float* sc_bound, int sc_n, float sc_k, float sc_r, int sc_on) {
  if (x[i].w == 0.0f) {
    x_next[i] = x[i];
    return;
  }
  jpgd_vertex(i, gather_vertex_system(i, x, x_tilde, inv_h2, adj_offsets, adj, stretch, bend, tets), JPGD_TAIL_ARGS);
}

/* solver.ordering: vertex_batches. Work-item b gathers the vertices
 * order[8b .. 8b + 8) (solver/vertex/vertex_layout vertex_lanes: 8
 * consecutive vertices, -1 padding the last batch) as 8 float lanes
 * (common/vertex_system_lanes.h), then steps them one after another: the
 * same bits as jpgd_step over them (every vertex reads x^k only). */
ATS_TASK void jpgd_step_lanes(int b, __global const float4* x, __global const float4* x_before, __global float4* x_next,
                              __global const float4* x_tilde, __global const int* adj_offsets, __global const int* adj,
                              __global const ats_distance_c* stretch, __global const ats_bend_c* bend,
                              __global const ats_tet_c* tets, __global const int* order, float inv_h2, float alpha,
                              float omega, float beta, int has_ground, float ground,
                              __global const ats_collider_c* colliders, int collider_count,
                              __global const ats_mesh_near* near, __global const float4* x_start, float inv_h,
                              __global const int4* sc_tris, __global const int2* sc_edges, __global const int* sc_inc,
                              __global const int* sc_vt, __global const int* sc_tv, __global const int* sc_ee,
                              __global const float* sc_bound, int sc_n, float sc_k, float sc_r, int sc_on) {
  int v[8];
  ATS_UNROLL for (int l = 0; l < 8; ++l) v[l] = order[8 * b + l];
  if (ats_gather_alone(sc_on, collider_count, inv_h)) {
    /* No contact term and no damping: the solves run as lanes too
     * (ats_m3_solve8, ats_m3_solve's operations), as in VBD's vbd_solve_lanes. */
    ats_f8 acc[12], dx[3];
    gather_vertex_system8_lanes(v, x, x_tilde, inv_h2, adj_offsets, adj, stretch, bend, tets, acc);
    const ats_i8 ok = ats_m3_solve8(acc, dx);
    for (int l = 0; l < 8; ++l) {
      if (v[l] < 0) continue;
      const float4 p = x[v[l]];
      if (p.w == 0.0f) {
        x_next[v[l]] = p;
        continue;
      }
      x_next[v[l]] = jpgd_next(p, ats_vs8_lane(acc, l), ats_solve8_lane(ok, dx, l), x_before[v[l]], alpha, omega, beta,
                               has_ground, ground);
    }
    return;
  }
  vertex_system s[8];
  gather_vertex_system8(v, x, x_tilde, inv_h2, adj_offsets, adj, stretch, bend, tets, s);
  for (int l = 0; l < 8; ++l) {
    if (v[l] >= 0) jpgd_vertex(v[l], s[l], JPGD_TAIL_ARGS);
  }
}
#undef JPGD_TAIL_ARGS
