/* Isometric bending energy (Bergou et al. 2006) of the XPBD bending
 * constraint C = sqrt(s) sum_i K_i x_i (common/xpbd_bending.h) with
 * compliance alpha, k = 1/alpha:
 *   E = 1/2 k |C|^2 = 1/2 k s |S|^2,   S = sum_i K_i x_i,
 *   grad_i E = k s K_i S,   H_ij = k s K_i K_j I.
 * E is quadratic in x, so the Hessian is constant and, as (K K^T) (x) I
 * times k s >= 0, already PSD: no projection needed. Zero for a flat rest
 * shape and under rigid motion of it (sum_i K_i = 0). */
#ifndef ATS_ENERGY_BENDING_H
#define ATS_ENERGY_BENDING_H

#include "common/ats_math.h"
#include "common/energy_mat3.h"

ATS_FN ats_vec3 ats_bend_weighted_sum(const ats_vec3 x[4], const ats_real K[4]) {
  ats_vec3 s = ats_v3(0, 0, 0);
  ATS_UNROLL for (int i = 0; i < 4; ++i) s = ats_add(s, ats_scale(x[i], K[i]));
  return s;
}

ATS_FN ats_real ats_bend_energy(const ats_vec3 x[4], const ats_real K[4], ats_real scale, ats_real stiffness) {
  const ats_vec3 s = ats_bend_weighted_sum(x, K);
  return (ats_real)0.5 * stiffness * scale * ats_dot(s, s);
}

/* Gradient with respect to x[i]. */
ATS_FN ats_vec3 ats_bend_gradient(const ats_vec3 x[4], const ats_real K[4], ats_real scale, ats_real stiffness, int i) {
  return ats_scale(ats_bend_weighted_sum(x, K), stiffness * scale * K[i]);
}

/* The block H_ij (the same for every position x). */
ATS_FN ats_mat3 ats_bend_hessian(const ats_real K[4], ats_real scale, ats_real stiffness, int i, int j) {
  return ats_m3_diag(stiffness * scale * K[i] * K[j]);
}

#endif
