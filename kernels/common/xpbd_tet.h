/* Strain-based XPBD for a StVK tetrahedron (Mueller et al. 2014, "Strain
 * based dynamics", with the compliance of XPBD, Macklin et al. 2016).
 * The StVK energy of common/energy_tet_stvk.h,
 *   V Psi = V [mu E:E + lambda/2 (tr E)^2],  E = 1/2 (F^T F - I),
 * is exactly a sum of 1/2 k_c C_c^2 over seven constraints, because
 * E:E = sum_i E_ii^2 + 2 sum_{i<j} E_ij^2:
 *   c = 0, 1, 2   C = E_cc   k = 2 mu V
 *   c = 3, 4, 5   C = E_01, E_02, E_12   k = 4 mu V
 *   c = 6         C = tr E   k = lambda V
 * Each is solved in turn (Gauss-Seidel inside the tet) with
 *   dlambda = (-C - alpha~ lambda) / (sum_a w_a |grad_a C|^2 + alpha~),
 *   alpha~ = 1 / (k h^2),  dx_a = w_a grad_a C dlambda.
 * Every constraint is zero at rest (E is computed without cancellation), so
 * the rest state is a fixed point in float; no constraint has to balance
 * another (the coupled deviatoric/hydrostatic form of Macklin & Mueller 2021
 * does, and lost the rest state of a multi-tet body to rounding).
 * Gradients: with f_i column i of F = sum_a x_a b_a^T (b_a the shape vectors
 * of common/tet_kinematics.h), E_ij = 1/2 f_i . f_j, so
 *   grad_a E_ij = 1/2 (b_a[j] f_i + b_a[i] f_j),  grad_a tr E = F b_a. */
#ifndef ATS_XPBD_TET_H
#define ATS_XPBD_TET_H

#include "common/ats_math.h"
#include "common/energy_mat3.h"
#include "common/energy_tet_stvk.h"
#include "common/tet_kinematics.h"

#define ATS_TET_STRAIN_CONSTRAINTS 7
#define ATS_TET_LAMBDA_STRIDE 8 /* lambdas stored per tet (7 used, padded) */

ATS_FN ats_real ats_v3_component(ats_vec3 v, int i) { return i == 0 ? v.x : (i == 1 ? v.y : v.z); }

/* The strain component (i, j) of constraint c < 6. */
ATS_FN int ats_tet_strain_i(int c) { return c < 3 ? c : (c == 5 ? 1 : 0); }
ATS_FN int ats_tet_strain_j(int c) { return c < 3 ? c : (c == 3 ? 1 : 2); }

/* k_c of the table above. */
ATS_FN ats_real ats_tet_strain_stiffness(int c, ats_real volume, ats_real mu, ats_real lambda) {
  if (c < 3) return 2 * mu * volume;
  if (c < 6) return 4 * mu * volume;
  return lambda * volume;
}

/* C_c from the Green strain E. */
ATS_FN ats_real ats_tet_strain_value(ats_mat3 e, int c) {
  if (c == 6) return ats_m3_trace(e);
  return ats_v3_component(e.r[ats_tet_strain_i(c)], ats_tet_strain_j(c));
}

/* grad_a C_c at deformation gradient f. */
ATS_FN ats_vec3 ats_tet_strain_gradient(ats_mat3 f, ats_mat3 dm_inv, int c, int a) {
  const ats_vec3 b = ats_tet_shape_vector(dm_inv, a);
  if (c == 6) return ats_m3_mul_v(f, b);
  const int i = ats_tet_strain_i(c);
  const int j = ats_tet_strain_j(c);
  const ats_mat3 ft = ats_m3_transpose(f); /* row i of F^T is column f_i */
  return ats_scale(ats_add(ats_scale(ft.r[i], ats_v3_component(b, j)), ats_scale(ft.r[j], ats_v3_component(b, i))),
                   (ats_real)0.5);
}

/* sum_c 1/2 k_c C_c^2: equals ats_tet_stvk_energy (tested). */
ATS_FN ats_real ats_tet_strain_energy(const ats_vec3 x[4], ats_mat3 dm_inv, ats_real volume, ats_real mu,
                                      ats_real lambda) {
  const ats_mat3 e = ats_tet_green_strain(ats_tet_deformation(x, dm_inv));
  ats_real sum = 0;
  ATS_UNROLL for (int c = 0; c < ATS_TET_STRAIN_CONSTRAINTS; ++c) {
    const ats_real v = ats_tet_strain_value(e, c);
    sum += (ats_real)0.5 * ats_tet_strain_stiffness(c, volume, mu, lambda) * v * v;
  }
  return sum;
}

/* One XPBD pass over the seven constraints of a tet: moves x (w = inverse
 * masses, 0 = pinned) and accumulates lambda[0..6] in place. A constraint
 * with k = 0 (lambda = 0 for Poisson ratio 0) has no energy and is skipped. */
ATS_FN void ats_xpbd_tet(ats_vec3 x[4], const ats_real w[4], ats_mat3 dm_inv, ats_real volume, ats_real mu,
                         ats_real lambda, ats_real lam[ATS_TET_LAMBDA_STRIDE], ats_real dt) {
  ATS_UNROLL for (int c = 0; c < ATS_TET_STRAIN_CONSTRAINTS; ++c) {
    const ats_real k = ats_tet_strain_stiffness(c, volume, mu, lambda);
    if (!(k > 0)) continue;
    const ats_real alpha = (ats_real)1 / (k * dt * dt);
    const ats_mat3 f = ats_tet_deformation(x, dm_inv);
    const ats_real value = ats_tet_strain_value(ats_tet_green_strain(f), c);
    ats_vec3 g[4];
    ats_real denom = alpha;
    ATS_UNROLL for (int a = 0; a < 4; ++a) {
      g[a] = ats_tet_strain_gradient(f, dm_inv, c, a);
      denom += w[a] * ats_dot(g[a], g[a]);
    }
    const ats_real dl = (-value - alpha * lam[c]) / denom;
    lam[c] += dl;
    ATS_UNROLL for (int a = 0; a < 4; ++a) x[a] = ats_add(x[a], ats_scale(g[a], w[a] * dl));
  }
}

/* The XPBD residuals C_c(x) + alpha~_c lambda_c of a tet (0 where k_c = 0). */
ATS_FN ats_real ats_xpbd_tet_residual(const ats_vec3 x[4], ats_mat3 dm_inv, ats_real volume, ats_real mu,
                                      ats_real lambda, ats_real lam_c, ats_real dt, int c) {
  const ats_real k = ats_tet_strain_stiffness(c, volume, mu, lambda);
  if (!(k > 0)) return 0;
  const ats_mat3 e = ats_tet_green_strain(ats_tet_deformation(x, dm_inv));
  return ats_tet_strain_value(e, c) + lam_c / (k * dt * dt);
}

#endif
