/* Terms of the incremental potential that XPBD run to convergence minimises
 * (He et al. 2025 §3.1, Eq. 1; Macklin et al. 2016, Eq. 4):
 *   E(x) = 1/2 h^-2 sum_i m_i |x_i - x~_i|^2 + sum_c 1/2 alpha_c^-1 |C_c(x)|^2,
 * one value per particle (inertia) and per constraint, written to
 * out[out_first + i]; the host sums them (in double). Positions are float4
 * with w = inverse mass; pinned particles (w = 0) are no variables and add 0.
 * A compliance of 0 has no finite energy: the host rejects it first.
 * Every kernel covers elements [first, first + count), independent of each
 * other, so a launch may be cut between devices. */
/* The stretch energy's error-free transforms must not be fused into FMAs. */
#pragma OPENCL FP_CONTRACT OFF

#include "common/ats_math.h"
#include "common/xpbd_types.h"
#include "common/energy_inertia.h"
#include "common/energy_stretch.h"
#include "common/energy_bending.h"

static inline ats_vec3 energy_xyz(float4 p) { return ats_v3(p.x, p.y, p.z); }

__kernel void energy_inertia(__global const float4* x, __global const float4* x_tilde, __global float* out,
                             int out_first, int first, int count, float inv_h2) {
  const int k = get_global_id(0);
  if (k >= count) return;
  const int i = first + k;
  const float4 p = x[i];
  out[out_first + i] = p.w > 0.0f ? ats_inertia_energy(energy_xyz(p), energy_xyz(x_tilde[i]), 1.0f / p.w, inv_h2)
                                  : 0.0f;
}

__kernel void energy_stretch(__global const float4* x, __global const ats_distance_c* c, __global float* out,
                             int out_first, int first, int count) {
  const int k = get_global_id(0);
  if (k >= count) return;
  const int i = first + k;
  const ats_distance_c con = c[i];
  out[out_first + i] =
      ats_stretch_energy(energy_xyz(x[con.a]), energy_xyz(x[con.b]), con.rest, 1.0f / con.compliance);
}

__kernel void energy_bend(__global const float4* x, __global const ats_bend_c* c, __global float* out,
                          int out_first, int first, int count) {
  const int k = get_global_id(0);
  if (k >= count) return;
  const int i = first + k;
  const ats_bend_c con = c[i];
  ats_vec3 p[4];
  for (int j = 0; j < 4; ++j) p[j] = energy_xyz(x[con.v[j]]);
  out[out_first + i] = ats_bend_energy(p, con.K, con.scale, 1.0f / con.compliance);
}
