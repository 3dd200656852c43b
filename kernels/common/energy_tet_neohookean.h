/* Stable neo-Hookean energy of a linear tetrahedron (Smith, de Goes & Kim
 * 2018, "Stable Neo-Hookean Flesh Simulation", ACM TOG 37(2), Eq. 13 without
 * the log term, shifted to be zero at rest):
 *   Psi(F) = mu/2 (I_C - 3) - mu (J - 1) + lambda'/2 (J - 1)^2,
 *   I_C = |F|^2,  J = det F,  lambda' = lambda + mu,
 * which equals their lambda'/2 (J - alpha)^2 + mu/2 (I_C - 3), alpha =
 * 1 + mu/lambda', minus its rest value mu^2 / (2 lambda'). The arguments mu,
 * lambda are the Lame parameters of linear elasticity: expanding at F = I + eps
 * gives Psi = mu |eps|^2 + (lambda' - mu)/2 (tr eps)^2 + O(eps^3), so
 * lambda' = lambda + mu matches it (Smith et al. §3.4 do the same for their
 * form with the log term). The energy is polynomial in F: it is zero with
 * zero stress at rest and finite, with finite stress and Hessian, for
 * inverted (J < 0) and flat (J = 0) tets, where it pushes back towards J = 1.
 * E = V Psi(F), F and the shape vectors b_a from common/tet_kinematics.h.
 *   P = mu F + s cof F,   s = lambda' (J - 1) - mu,
 *   H_ab = V [ mu (b_a . b_b) I + lambda' (C b_a)(C b_b)^T - s [F (b_a x b_b)]_x ],
 * C = cof F = dJ/dF, the last term from the Hessian of J, which is linear in F
 * (Smith et al. §4.2, Eq. 29). */
#ifndef ATS_ENERGY_TET_NEOHOOKEAN_H
#define ATS_ENERGY_TET_NEOHOOKEAN_H

#include "common/ats_math.h"
#include "common/energy_mat3.h"
#include "common/tet_kinematics.h"

/* Psi(F), written in G = F - I so that the O(|G|) terms cancel exactly:
 * mu/2 (I_C - 3) - mu (J - 1) = mu/2 |G|^2 - mu (s2(G) + det G). */
ATS_FN ats_real ats_tet_nh_energy_density(ats_mat3 f, ats_real mu, ats_real lambda) {
  const ats_mat3 g = ats_m3_sub(f, ats_m3_diag(1));
  const ats_real dj = ats_tet_volume_change(g);
  return (ats_real)0.5 * mu * ats_m3_ddot(g, g) - mu * (ats_m3_minor_sum(g) + ats_m3_det(g)) +
         (ats_real)0.5 * (lambda + mu) * dj * dj;
}

/* P = mu (F - cof F) + lambda' (J - 1) cof F, with
 * F - cof F = G + G^T - (tr G) I - cof G (no cancellation near rest). */
ATS_FN ats_mat3 ats_tet_nh_stress(ats_mat3 f, ats_real mu, ats_real lambda) {
  const ats_mat3 g = ats_m3_sub(f, ats_m3_diag(1));
  const ats_mat3 shear =
      ats_m3_sub(ats_m3_add(g, ats_m3_transpose(g)), ats_m3_add(ats_m3_diag(ats_m3_trace(g)), ats_m3_cofactor(g)));
  return ats_m3_add(ats_m3_scale(shear, mu),
                    ats_m3_scale(ats_m3_cofactor(f), (lambda + mu) * ats_tet_volume_change(g)));
}

ATS_FN ats_real ats_tet_nh_energy(const ats_vec3 x[4], ats_mat3 dm_inv, ats_real volume, ats_real mu, ats_real lambda) {
  return volume * ats_tet_nh_energy_density(ats_tet_deformation(x, dm_inv), mu, lambda);
}

/* Gradient with respect to x[a]: V P b_a. */
ATS_FN ats_vec3 ats_tet_nh_gradient(const ats_vec3 x[4], ats_mat3 dm_inv, ats_real volume, ats_real mu, ats_real lambda,
                                    int a) {
  const ats_mat3 p = ats_tet_nh_stress(ats_tet_deformation(x, dm_inv), mu, lambda);
  return ats_scale(ats_m3_mul_v(p, ats_tet_shape_vector(dm_inv, a)), volume);
}

/* The block H_ab = d^2 E / dx_a dx_b (H_ba = H_ab^T). */
ATS_FN ats_mat3 ats_tet_nh_hessian(const ats_vec3 x[4], ats_mat3 dm_inv, ats_real volume, ats_real mu, ats_real lambda,
                                   int a, int b) {
  const ats_mat3 f = ats_tet_deformation(x, dm_inv);
  const ats_mat3 c = ats_m3_cofactor(f);
  const ats_vec3 ba = ats_tet_shape_vector(dm_inv, a);
  const ats_vec3 bb = ats_tet_shape_vector(dm_inv, b);
  const ats_real lambda_s = lambda + mu;
  const ats_real s = lambda_s * ats_tet_volume_change(ats_m3_sub(f, ats_m3_diag(1))) - mu;
  ats_mat3 h = ats_m3_diag(mu * ats_dot(ba, bb));
  h = ats_m3_add(h, ats_m3_outer(ats_m3_mul_v(c, ba), ats_scale(ats_m3_mul_v(c, bb), lambda_s)));
  h = ats_m3_sub(h, ats_m3_hat(ats_scale(ats_m3_mul_v(f, ats_v3_cross(ba, bb)), s)));
  return ats_m3_scale(h, volume);
}

/* The diagonal block H_aa as vertex block descent needs it (Chen et al.
 * 2024): PSD. No projection is needed: b_a x b_a = 0 removes the indefinite
 * Hessian-of-J term, leaving H_aa = V [mu |b_a|^2 I + lambda' (C b_a)(C b_a)^T],
 * PSD for V, mu >= 0 and lambda' = lambda + mu >= 0 (true for every Poisson
 * ratio in (-1, 1/2)); lambda' is clamped at 0 to keep it so for any input.
 * It is exactly ats_tet_nh_hessian(..., a, a) there, inverted tets included. */
ATS_FN ats_mat3 ats_tet_nh_hessian_diag_psd(const ats_vec3 x[4], ats_mat3 dm_inv, ats_real volume, ats_real mu,
                                            ats_real lambda, int a) {
  const ats_vec3 ba = ats_tet_shape_vector(dm_inv, a);
  const ats_vec3 cb = ats_m3_mul_v(ats_m3_cofactor(ats_tet_deformation(x, dm_inv)), ba);
  const ats_real lambda_s = lambda + mu > 0 ? lambda + mu : (ats_real)0;
  return ats_m3_scale(ats_m3_add(ats_m3_diag(mu * ats_dot(ba, ba)), ats_m3_outer(cb, ats_scale(cb, lambda_s))), volume);
}

#endif
