/* One vertex's force and Hessian block from the incremental potential
 * (He et al. 2025 §3.1): f = -(m/h^2)(x - x~) - sum_e grad_i E_e and
 * H = (m/h^2) I + sum_e H_ii^e (stretch blocks projected PSD), gathered over
 * the elements touching the vertex through a CSR list (NvCloth-style, no
 * atomics). Entry code = element << 4 | kind << 2 | slot; kind 0 stretch
 * (slot 0/1), kind 1 bending (slot 0..3), kind 2 tetrahedron (slot 0..3;
 * stable neo-Hookean or StVK, with the PSD diagonal block).
 * OpenCL only: it reads global memory. */
#include "common/energy_bending.h"
#include "common/energy_inertia.h"
#include "common/energy_stretch.h"
#include "common/energy_tet_neohookean.h"
#include "common/energy_tet_stvk.h"
#include "common/element_types.h"

typedef struct {
  ats_vec3 f;
  ats_mat3 h;
} vertex_system;

static inline ats_vec3 vs_xyz(float4 p) { return ats_v3(p.x, p.y, p.z); }

static inline vertex_system gather_vertex_system(int i, __global const float4* x, __global const float4* x_tilde,
                                                 float inv_h2, __global const int* adj_offsets,
                                                 __global const int* adj, __global const ats_distance_c* stretch,
                                                 __global const ats_bend_c* bend, __global const ats_tet_c* tets) {
  const float4 p = x[i];
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
      for (int j = 0; j < 4; ++j) q[j] = vs_xyz(x[t.v[j]]);
      ats_mat3 dm;
      for (int r = 0; r < 3; ++r) dm.r[r] = ats_v3(t.dm_inv[3 * r], t.dm_inv[3 * r + 1], t.dm_inv[3 * r + 2]);
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
      for (int j = 0; j < 4; ++j) q[j] = vs_xyz(x[c.v[j]]);
      const float stiffness = 1.0f / c.compliance;
      s.f = ats_sub(s.f, ats_bend_gradient(q, c.K, c.scale, stiffness, slot));
      s.h = ats_m3_add(s.h, ats_bend_hessian(c.K, c.scale, stiffness, slot, slot));
    }
  }
  return s;
}
