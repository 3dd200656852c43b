/* Vertex Block Descent (Chen et al. 2024): Gauss-Seidel over vertex colors;
 * each vertex of a color takes one 3x3 Newton step on the incremental
 * potential with its neighbours fixed, skipped when its block is near
 * singular. Vertices of one color share no element. */
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

/* Vertex i's step from its gathered system s: spring damping, collider and
 * surface contact terms, the 3x3 solve, the ground and the bounds. sc_x_iter:
 * the positions at the iteration's start, sc_color: every particle's colour
 * (-1: none), for the contact pairs (contact/self_contact_terms.h). */
static inline void vbd_step(int i, vertex_system s, __global float4* x, __global const int* adj_offsets,
                            __global const int* adj, __global const ats_distance_c* stretch, float inv_h2,
                            int has_ground, float ground, __global const ats_collider_c* colliders, int collider_count,
                            __global const ats_mesh_near* near, __global const float4* x_start, float inv_h,
                            __global const int4* sc_tris, __global const int2* sc_edges, __global const int* sc_inc,
                            __global const int* sc_vt, __global const int* sc_tv, __global const int* sc_ee,
                            __global const float* sc_bound, int sc_n, float sc_k, float sc_r, int sc_on,
                            __global const float4* sc_x_iter, __global const int* sc_color) {
  const float4 p = x[i];
  __global const ats_mesh_near* mine = ats_near_of(colliders, collider_count, near, i);
  s = add_self_contact_terms_gs(
      add_contact_terms(add_spring_damping(s, i, x, x_start, inv_h, adj_offsets, adj, stretch), vs_xyz(p), p.w, inv_h2,
                        colliders, collider_count, mine),
      i, x, sc_x_iter, sc_color, sc_tris, sc_edges, sc_inc, sc_n, sc_vt, sc_tv, sc_ee, sc_k, sc_r, sc_on);
  const ats_solve3 d = sc_contact_step(s, i, x, sc_x_iter, sc_color, sc_tris, sc_edges, sc_inc, sc_n, sc_vt, sc_tv,
                                       sc_ee, sc_k, sc_r, sc_on);
  if (!d.ok) return;
  ats_vec3 step = d.x;
  if (has_ground && p.y + step.y < ground) step = ats_vertex_step_above_ground(s.h, s.f, step, p.y, ground);
  x[i] = sc_out_of_colliders(
      sc_bounded_step((float4)(p.x + step.x, p.y + step.y, p.z + step.z, p.w), i, x_start, sc_bound, sc_on), colliders,
      collider_count, mine, sc_on);
}

/* Vertices order[first .. first + count) of one color. */
ATS_TASK void vbd_solve(int k, __global float4* x, __global const float4* x_tilde, __global const int* adj_offsets,
                        __global const int* adj, __global const ats_distance_c* stretch,
                        __global const ats_bend_c* bend, __global const ats_tet_c* tets, __global const int* order,
                        float inv_h2, int has_ground, float ground, __global const ats_collider_c* colliders,
                        int collider_count, __global const ats_mesh_near* near, __global const float4* x_start,
                        float inv_h, __global const int4* sc_tris, __global const int2* sc_edges,
                        __global const int* sc_inc, __global const int* sc_vt, __global const int* sc_tv,
                        __global const int* sc_ee, __global const float* sc_bound, int sc_n, float sc_k, float sc_r,
                        int sc_on, __global const float4* sc_x_iter, __global const int* sc_color) {
  const int i = order[k];
  vbd_step(i, gather_vertex_system(i, x, x_tilde, inv_h2, adj_offsets, adj, stretch, bend, tets), x, adj_offsets, adj,
           stretch, inv_h2, has_ground, ground, colliders, collider_count, near, x_start, inv_h, sc_tris, sc_edges,
           sc_inc, sc_vt, sc_tv, sc_ee, sc_bound, sc_n, sc_k, sc_r, sc_on, sc_x_iter, sc_color);
}

/* solver.ordering: color_batches. Work-item b gathers the vertices
 * order[8b .. 8b + 8) of one color (solver/vertex/vertex_layout: the colors
 * padded to whole batches, -1 a padding lane) as 8 float lanes
 * (common/vertex_system_lanes.h), then steps them one after another: the
 * same bits as vbd_solve over them. */
ATS_TASK void vbd_solve_lanes(int b, __global float4* x, __global const float4* x_tilde,
                              __global const int* adj_offsets, __global const int* adj,
                              __global const ats_distance_c* stretch, __global const ats_bend_c* bend,
                              __global const ats_tet_c* tets, __global const int* order, float inv_h2, int has_ground,
                              float ground, __global const ats_collider_c* colliders, int collider_count,
                              __global const ats_mesh_near* near, __global const float4* x_start, float inv_h,
                              __global const int4* sc_tris, __global const int2* sc_edges, __global const int* sc_inc,
                              __global const int* sc_vt, __global const int* sc_tv, __global const int* sc_ee,
                              __global const float* sc_bound, int sc_n, float sc_k, float sc_r, int sc_on,
                              __global const float4* sc_x_iter, __global const int* sc_color) {
  int v[8];
  ATS_UNROLL for (int l = 0; l < 8; ++l) v[l] = order[8 * b + l];
  if (ats_gather_alone(sc_on, collider_count, inv_h)) {
    /* No contact term and no damping: vbd_step is the solve and the ground,
     * and the solve runs as lanes too (ats_m3_solve8, the same operations). */
    ats_f8 acc[12];
    gather_vertex_system8_lanes(v, x, x_tilde, inv_h2, adj_offsets, adj, stretch, bend, tets, acc);
    ats_vbd_step8(v, acc, x, has_ground, ground);
    return;
  }
  vertex_system s[8];
  gather_vertex_system8(v, x, x_tilde, inv_h2, adj_offsets, adj, stretch, bend, tets, s);
  for (int l = 0; l < 8; ++l) {
    if (v[l] < 0) continue;
    vbd_step(v[l], s[l], x, adj_offsets, adj, stretch, inv_h2, has_ground, ground, colliders, collider_count, near,
             x_start, inv_h, sc_tris, sc_edges, sc_inc, sc_vt, sc_tv, sc_ee, sc_bound, sc_n, sc_k, sc_r, sc_on,
             sc_x_iter, sc_color);
  }
}
