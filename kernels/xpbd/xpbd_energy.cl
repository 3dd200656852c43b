/* Terms of the incremental potential that XPBD run to convergence minimises
 * (He et al. 2025 §3.1, Eq. 1; Macklin et al. 2016, Eq. 4):
 *   E(x) = 1/2 h^-2 sum_i m_i |x_i - x~_i|^2 + sum_c 1/2 alpha_c^-1 |C_c(x)|^2
 *        + sum_tet V Psi(F),
 * one value per particle (inertia), per constraint and per tet, written to
 * out[out_first + i]; the host sums them (in double). Positions are float4
 * with w = inverse mass; pinned particles (w = 0) are no variables and add 0.
 * A compliance of 0 has no finite energy: the host rejects it first.
 * Every kernel covers elements [first, first + count), independent of each
 * other, so a launch may be cut between devices. */
/* The stretch energy's error-free transforms must not be fused into FMAs. */
#pragma OPENCL FP_CONTRACT OFF

#include "common/ats_math.h"
#include "common/task.h"
#include "common/element_types.h"
#include "common/energy_inertia.h"
#include "common/energy_stretch.h"
#include "common/energy_bend_element.h"
#include "common/energy_tet_neohookean.h"
#include "common/energy_tet_stvk.h"

static inline ats_vec3 energy_xyz(float4 p) { return ats_v3(p.x, p.y, p.z); }

ATS_TASK void energy_inertia(int i, __global const float4* x, __global const float4* x_tilde, __global float* out,
                             int out_first, float inv_h2) {
  const float4 p = x[i];
  out[out_first + i] =
      p.w > 0.0f ? ats_inertia_energy(energy_xyz(p), energy_xyz(x_tilde[i]), 1.0f / p.w, inv_h2) : 0.0f;
}

ATS_TASK void energy_stretch(int i, __global const float4* x, __global const ats_distance_c* c, __global float* out,
                             int out_first) {
  const ats_distance_c con = c[i];
  out[out_first + i] = ats_stretch_energy(energy_xyz(x[con.a]), energy_xyz(x[con.b]), con.rest, 1.0f / con.compliance);
}

ATS_TASK void energy_bend(int i, __global const float4* x, __global const ats_bend_c* c, __global float* out,
                          int out_first) {
  const ats_bend_c con = c[i];
  ats_vec3 p[4];
  ATS_UNROLL for (int j = 0; j < 4; ++j) p[j] = energy_xyz(x[con.v[j]]);
  out[out_first + i] = ats_bend_element_energy(con.model, p, con.K, con.scale, 1.0f / con.compliance, con.rest_angle);
}

/* One tet: stable neo-Hookean or StVK (ats_tet_c.model); the host has
 * rejected mu <= 0, lambda < 0 and unknown models. */
ATS_TASK void energy_tet(int i, __global const float4* x, __global const ats_tet_c* c, __global float* out,
                         int out_first) {
  const ats_tet_c t = c[i];
  ats_vec3 p[4];
  ATS_UNROLL for (int j = 0; j < 4; ++j) p[j] = energy_xyz(x[t.v[j]]);
  ats_mat3 dm_inv;
  ATS_UNROLL for (int r = 0; r < 3; ++r) dm_inv.r[r] =
      ats_v3(t.dm_inv[3 * r], t.dm_inv[3 * r + 1], t.dm_inv[3 * r + 2]);
  out[out_first + i] = t.model == ATS_TET_STVK ? ats_tet_stvk_energy(p, dm_inv, t.volume, t.mu, t.lambda)
                                               : ats_tet_nh_energy(p, dm_inv, t.volume, t.mu, t.lambda);
}
