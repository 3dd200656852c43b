/* St. Venant-Kirchhoff energy of a linear tetrahedron (Sifakis & Barbic
 * 2012, "FEM simulation of 3D deformable solids", SIGGRAPH course notes,
 * §3.3 and §4.2):
 *   Psi(F) = mu |E|^2 + lambda/2 (tr E)^2,   E = 1/2 (F^T F - I),
 *   P = F S,   S = 2 mu E + lambda (tr E) I,
 * mu, lambda the Lame parameters (so it agrees with linear elasticity to
 * second order in the strain). E = V Psi(F), F and the shape vectors b_a from
 * common/tet_kinematics.h. Perturbing x_b by u gives dF = u b_b^T, hence
 *   H_ab = V [ (b_b^T S b_a) I + mu (F b_b)(F b_a)^T + mu (b_a . b_b) F F^T
 *              + lambda (F b_a)(F b_b)^T ].
 * StVK is polynomial in F: finite for inverted tets (but it does not resist
 * inversion: it softens under compression, a known weakness, Sifakis &
 * Barbic §3.3). The first term makes H indefinite under compression, hence
 * the projected diagonal block. */
#ifndef ATS_ENERGY_TET_STVK_H
#define ATS_ENERGY_TET_STVK_H

#include "common/ats_math.h"
#include "common/energy_mat3.h"
#include "common/tet_kinematics.h"

/* Green strain E = 1/2 (G + G^T + G^T G), G = F - I (no cancellation at rest). */
ATS_FN ats_mat3 ats_tet_green_strain(ats_mat3 f) {
  const ats_mat3 g = ats_m3_sub(f, ats_m3_diag(1));
  const ats_mat3 gt = ats_m3_transpose(g);
  return ats_m3_scale(ats_m3_add(ats_m3_add(g, gt), ats_m3_mul(gt, g)), (ats_real)0.5);
}

ATS_FN ats_real ats_tet_stvk_energy_density(ats_mat3 f, ats_real mu, ats_real lambda) {
  const ats_mat3 e = ats_tet_green_strain(f);
  const ats_real tr = ats_m3_trace(e);
  return mu * ats_m3_ddot(e, e) + (ats_real)0.5 * lambda * tr * tr;
}

/* Second Piola-Kirchhoff stress S = 2 mu E + lambda tr(E) I. */
ATS_FN ats_mat3 ats_tet_stvk_pk2(ats_mat3 f, ats_real mu, ats_real lambda) {
  const ats_mat3 e = ats_tet_green_strain(f);
  return ats_m3_add(ats_m3_scale(e, 2 * mu), ats_m3_diag(lambda * ats_m3_trace(e)));
}

/* First Piola-Kirchhoff stress P = F S. */
ATS_FN ats_mat3 ats_tet_stvk_stress(ats_mat3 f, ats_real mu, ats_real lambda) {
  return ats_m3_mul(f, ats_tet_stvk_pk2(f, mu, lambda));
}

ATS_FN ats_real ats_tet_stvk_energy(const ats_vec3 x[4], ats_mat3 dm_inv, ats_real volume, ats_real mu,
                                    ats_real lambda) {
  return volume * ats_tet_stvk_energy_density(ats_tet_deformation(x, dm_inv), mu, lambda);
}

/* Gradient with respect to x[a]: V P b_a. */
ATS_FN ats_vec3 ats_tet_stvk_gradient(const ats_vec3 x[4], ats_mat3 dm_inv, ats_real volume, ats_real mu,
                                      ats_real lambda, int a) {
  const ats_mat3 p = ats_tet_stvk_stress(ats_tet_deformation(x, dm_inv), mu, lambda);
  return ats_scale(ats_m3_mul_v(p, ats_tet_shape_vector(dm_inv, a)), volume);
}

/* The block H_ab = d^2 E / dx_a dx_b (H_ba = H_ab^T). */
ATS_FN ats_mat3 ats_tet_stvk_hessian(const ats_vec3 x[4], ats_mat3 dm_inv, ats_real volume, ats_real mu,
                                     ats_real lambda, int a, int b) {
  const ats_mat3 f = ats_tet_deformation(x, dm_inv);
  const ats_mat3 s = ats_tet_stvk_pk2(f, mu, lambda);
  const ats_vec3 ba = ats_tet_shape_vector(dm_inv, a);
  const ats_vec3 bb = ats_tet_shape_vector(dm_inv, b);
  const ats_vec3 ya = ats_m3_mul_v(f, ba);
  const ats_vec3 yb = ats_m3_mul_v(f, bb);
  ats_mat3 h = ats_m3_diag(ats_dot(bb, ats_m3_mul_v(s, ba)));
  h = ats_m3_add(h, ats_m3_outer(yb, ats_scale(ya, mu)));
  h = ats_m3_add(h, ats_m3_scale(ats_m3_mul(f, ats_m3_transpose(f)), mu * ats_dot(ba, bb)));
  h = ats_m3_add(h, ats_m3_outer(ya, ats_scale(yb, lambda)));
  return ats_m3_scale(h, volume);
}

/* H_aa with negative eigenvalues clamped at 0 (ats_m3_project_psd), for
 * vertex block descent (Chen et al. 2024). */
ATS_FN ats_mat3 ats_tet_stvk_hessian_diag_psd(const ats_vec3 x[4], ats_mat3 dm_inv, ats_real volume, ats_real mu,
                                              ats_real lambda, int a) {
  return ats_m3_project_psd(ats_tet_stvk_hessian(x, dm_inv, volume, mu, lambda, a, a));
}

#endif
