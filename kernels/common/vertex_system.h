/* One vertex's force and Hessian block from the incremental potential
 * (He et al. 2025 §3.1): f = -(m/h^2)(x - x~) - sum_e grad_i E_e and
 * H = (m/h^2) I + sum_e H_ii^e (stretch blocks projected PSD), gathered over
 * the elements touching the vertex through a CSR list (NvCloth-style, no
 * atomics). Entry code = element << 4 | kind << 2 | slot; kind 0 stretch
 * (slot 0/1), kind 1 bending (slot 0..3; isometric or dihedral), kind 2 tetrahedron (slot 0..3;
 * stable neo-Hookean or StVK, with the PSD diagonal block).
 * In the common subset of C, C++ and OpenCL C (common/ats_math.h): the
 * kernels (through common/vertex_system.cl) and the host VBD reference run
 * this one gather; host code defines ats_float4 before including it. Float
 * only, and the stretch terms need FP contraction off (energy_stretch.h). */
#ifndef ATS_VERTEX_SYSTEM_H
#define ATS_VERTEX_SYSTEM_H

#include "common/element_types.h"
#include "common/energy_bend_element.h"
#include "common/energy_inertia.h"
#include "common/energy_spring_damping.h"
#include "common/energy_stretch.h"
#include "common/energy_tet_neohookean.h"
#include "common/energy_tet_stvk.h"

typedef struct {
  ats_vec3 f;
  ats_mat3 h;
} vertex_system;

ATS_FN ats_vec3 vs_xyz(ats_float4 p) { return ats_v3(p.x, p.y, p.z); }

ATS_FN vertex_system gather_vertex_system(int i, ATS_GLOBAL const ats_float4* x, ATS_GLOBAL const ats_float4* x_tilde,
                                          float inv_h2, ATS_GLOBAL const int* adj_offsets, ATS_GLOBAL const int* adj,
                                          ATS_GLOBAL const ats_distance_c* stretch, ATS_GLOBAL const ats_bend_c* bend,
                                          ATS_GLOBAL const ats_tet_c* tets) {
  const ats_float4 p = x[i];
  const ats_vec3 xi = vs_xyz(p);
  const float mass = 1.0f / p.w;
  vertex_system s;
  s.f = ats_scale(ats_inertia_gradient(xi, vs_xyz(x_tilde[i]), mass, inv_h2), -1.0f);
  s.h = ats_inertia_hessian(mass, inv_h2);
  for (int k = adj_offsets[i]; k < adj_offsets[i + 1]; ++k) {
    const int code = adj[k];
    const int e = code >> 4, kind = (code >> 2) & 3, slot = code & 3;
    if (kind == 0) {
      const ats_distance_c c = stretch[e];
      const float stiffness = 1.0f / c.compliance;
      const ats_vec3 g = ats_stretch_gradient(vs_xyz(x[c.a]), vs_xyz(x[c.b]), c.rest, stiffness);
      s.f = slot == 0 ? ats_sub(s.f, g) : ats_add(s.f, g);
      s.h = ats_m3_add(s.h, ats_stretch_hessian(vs_xyz(x[c.a]), vs_xyz(x[c.b]), c.rest, stiffness, 1));
    } else if (kind == 2) {
      const ats_tet_c t = tets[e];
      ats_vec3 q[4];
      ATS_UNROLL for (int j = 0; j < 4; ++j) q[j] = vs_xyz(x[t.v[j]]);
      ats_mat3 dm;
      ATS_UNROLL for (int r = 0; r < 3; ++r) dm.r[r] =
          ats_v3(t.dm_inv[3 * r], t.dm_inv[3 * r + 1], t.dm_inv[3 * r + 2]);
      if (t.model == ATS_TET_STVK) {
        s.f = ats_sub(s.f, ats_tet_stvk_gradient(q, dm, t.volume, t.mu, t.lambda, slot));
        s.h = ats_m3_add(s.h, ats_tet_stvk_hessian_diag_psd(q, dm, t.volume, t.mu, t.lambda, slot));
      } else {
        s.f = ats_sub(s.f, ats_tet_nh_gradient(q, dm, t.volume, t.mu, t.lambda, slot));
        s.h = ats_m3_add(s.h, ats_tet_nh_hessian_diag_psd(q, dm, t.volume, t.mu, t.lambda, slot));
      }
    } else {
      const ats_bend_c c = bend[e];
      ats_vec3 q[4];
      ATS_UNROLL for (int j = 0; j < 4; ++j) q[j] = vs_xyz(x[c.v[j]]);
      const float stiffness = 1.0f / c.compliance;
      s.f = ats_sub(s.f, ats_bend_element_gradient(c.model, q, c.K, c.scale, stiffness, c.rest_angle, slot));
      s.h = ats_m3_add(s.h, ats_bend_element_hessian(c.model, q, c.K, c.scale, stiffness, slot, slot));
    }
  }
  return s;
}

/* Adds the springs' material damping (common/energy_spring_damping.h) to
 * vertex i's system: for each spring with damping beta > 0, c/h = beta k / h
 * with the direction at the substep's start x_start. inv_h = 1/h (the
 * substep, not the inertia step of air drag); the plans pass 0 when no
 * spring is damped and then skip this. */
ATS_FN vertex_system add_spring_damping(vertex_system s, int i, ATS_GLOBAL const ats_float4* x,
                                        ATS_GLOBAL const ats_float4* x_start, float inv_h,
                                        ATS_GLOBAL const int* adj_offsets, ATS_GLOBAL const int* adj,
                                        ATS_GLOBAL const ats_distance_c* stretch) {
  if (!(inv_h > 0.0f)) return s;
  for (int k = adj_offsets[i]; k < adj_offsets[i + 1]; ++k) {
    const int code = adj[k];
    if (((code >> 2) & 3) != 0) continue;
    const ats_distance_c c = stretch[code >> 4];
    if (!(c.damping > 0.0f)) continue;
    const float c_over_h = c.damping / c.compliance * inv_h;
    const ats_vec3 xa0 = vs_xyz(x_start[c.a]), xb0 = vs_xyz(x_start[c.b]);
    const ats_vec3 g = ats_spring_damping_gradient(vs_xyz(x[c.a]), vs_xyz(x[c.b]), xa0, xb0, c_over_h);
    s.f = (code & 3) == 0 ? ats_sub(s.f, g) : ats_add(s.f, g);
    s.h = ats_m3_add(s.h, ats_spring_damping_hessian(xa0, xb0, c_over_h));
  }
  return s;
}

#endif
