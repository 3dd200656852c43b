/* One particle's force for explicit integration (seed 001: mass-spring
 * cloth and tetrahedral bodies): gravity, air drag and minus the gradient
 * of every element touching the particle, gathered over the CSR
 * particle -> element list (NvCloth-style: no atomics, no locks; entry codes
 * as in common/vertex_system.h). The elements' order in the list is
 * ascending per kind, so the sum equals a serial sum over the elements in
 * index order, bit for bit. Springs are the stretch elements
 * (E = 1/2 k (|x_a - x_b| - L)^2, k = 1/compliance); bending and tets use
 * the same energies as the implicit methods. */
#ifndef ATS_VERTEX_FORCE_H
#define ATS_VERTEX_FORCE_H

#include "common/element_types.h"
#include "common/energy_bend_element.h"
#include "common/energy_spring_damping.h"
#include "common/energy_stretch.h"
#include "common/energy_tet_neohookean.h"
#include "common/energy_tet_stvk.h"

ATS_FN ats_vec3 vf_xyz(ats_float4 p) { return ats_v3(p.x, p.y, p.z); }

/* The spring force on its particle a: minus the stretch energy's gradient
 * (common/energy_stretch.h), -k (|d| - L) d/|d|, d = x_a - x_b; b gets its
 * negation. */
ATS_FN ats_vec3 ats_spring_force(ats_vec3 xa, ats_vec3 xb, float rest, float stiffness) {
  return ats_scale(ats_stretch_gradient(xa, xb, rest, stiffness), -1.0f);
}

/* Elements' force on particle i (no gravity, no drag); springs with
 * damping > 0 add c ((v_b - v_a) . n) n, c = damping / compliance
 * (common/energy_spring_damping.h), at the stage velocities v. */
ATS_FN ats_vec3 gather_element_force(int i, ATS_GLOBAL const ats_float4* x, ATS_GLOBAL const ats_float4* v,
                                     ATS_GLOBAL const int* adj_offsets, ATS_GLOBAL const int* adj,
                                     ATS_GLOBAL const ats_distance_c* stretch, ATS_GLOBAL const ats_bend_c* bend,
                                     ATS_GLOBAL const ats_tet_c* tets) {
  ats_vec3 f = ats_v3(0.0f, 0.0f, 0.0f);
  for (int k = adj_offsets[i]; k < adj_offsets[i + 1]; ++k) {
    const int code = adj[k];
    const int e = code >> 4, kind = (code >> 2) & 3, slot = code & 3;
    if (kind == 0) {
      const ats_distance_c c = stretch[e];
      ats_vec3 g = ats_spring_force(vf_xyz(x[c.a]), vf_xyz(x[c.b]), c.rest, 1.0f / c.compliance);
      if (c.damping > 0.0f) {
        g = ats_add(g, ats_spring_damping_force(vf_xyz(x[c.a]), vf_xyz(x[c.b]), vf_xyz(v[c.a]), vf_xyz(v[c.b]),
                                                c.damping / c.compliance));
      }
      f = slot == 0 ? ats_add(f, g) : ats_sub(f, g);
    } else if (kind == 1) {
      const ats_bend_c c = bend[e];
      ats_vec3 q[4];
      ATS_UNROLL for (int j = 0; j < 4; ++j) q[j] = vf_xyz(x[c.v[j]]);
      f = ats_sub(f, ats_bend_element_gradient(c.model, q, c.K, c.scale, 1.0f / c.compliance, c.rest_angle, slot));
    } else {
      const ats_tet_c t = tets[e];
      ats_vec3 q[4];
      ATS_UNROLL for (int j = 0; j < 4; ++j) q[j] = vf_xyz(x[t.v[j]]);
      ats_mat3 dm;
      ATS_UNROLL for (int r = 0; r < 3; ++r) dm.r[r] =
          ats_v3(t.dm_inv[3 * r], t.dm_inv[3 * r + 1], t.dm_inv[3 * r + 2]);
      f = ats_sub(f, t.model == ATS_TET_STVK ? ats_tet_stvk_gradient(q, dm, t.volume, t.mu, t.lambda, slot)
                                             : ats_tet_nh_gradient(q, dm, t.volume, t.mu, t.lambda, slot));
    }
  }
  return f;
}

/* Acceleration of particle i: g - c v + f/m; 0 for a pinned particle. */
ATS_FN ats_vec3 particle_acceleration(int i, ATS_GLOBAL const ats_float4* x, ATS_GLOBAL const ats_float4* v,
                                      ATS_GLOBAL const int* adj_offsets, ATS_GLOBAL const int* adj,
                                      ATS_GLOBAL const ats_distance_c* stretch, ATS_GLOBAL const ats_bend_c* bend,
                                      ATS_GLOBAL const ats_tet_c* tets, ats_vec3 g, float drag) {
  const float w = x[i].w;
  if (w == 0.0f) return ats_v3(0.0f, 0.0f, 0.0f);
  const ats_vec3 f = gather_element_force(i, x, v, adj_offsets, adj, stretch, bend, tets);
  return ats_add(ats_sub(g, ats_scale(vf_xyz(v[i]), drag)), ats_scale(f, w));
}

#endif
