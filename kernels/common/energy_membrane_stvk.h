/* St. Venant-Kirchhoff membrane energy of a linear triangle in 3D (the
 * plane-stress StVK of Sifakis & Barbic 2012, SIGGRAPH course notes, with the
 * 3x2 deformation gradient of a triangle; e.g. Volino et al. 2009, "A simple
 * approach to nonlinear tensile stiffness for accurate cloth simulation"):
 *   Ds = [x1 - x0, x2 - x0] (3x2),  F = Ds Dm^-1 (3x2),
 *   Psi(F) = mu |E|^2 + lambda/2 (tr E)^2,   E = 1/2 (F^T F - I) (2x2),
 * Dm the 2x2 matrix of the rest edges in an orthonormal frame of the rest
 * triangle (ats_membrane_rest_of), E = A Psi with A the rest area. mu and
 * lambda are membrane (per unit area) Lame parameters: thickness times the 3D
 * mu and the plane-stress 2 mu lambda / (lambda + 2 mu).
 * As for tets (common/energy_tet_stvk.h), F = sum_a x_a b_a^T with b_a in R^2
 * (rows of Dm^-1, b_0 = -b_1 - b_2), P = F S, S = 2 mu E + lambda tr(E) I,
 *   grad_a = A P b_a,
 *   H_ab = A [ (b_b^T S b_a) I + mu (F b_b)(F b_a)^T + mu (b_a . b_b) F F^T
 *              + lambda (F b_a)(F b_b)^T ]   (3x3). */
#ifndef ATS_ENERGY_MEMBRANE_STVK_H
#define ATS_ENERGY_MEMBRANE_STVK_H

#include "common/ats_math.h"
#include "common/energy_mat3.h"

typedef struct {
  ats_real x, y;
} ats_vec2;

/* Row-major 2x2. */
typedef struct {
  ats_real a00, a01, a10, a11;
} ats_mat2;

/* 3x2, by columns: F = [c0 c1]. */
typedef struct {
  ats_vec3 c[2];
} ats_mat32;

typedef struct {
  ats_mat2 dm_inv;
  ats_real area;
} ats_membrane_rest;

/* Rest frame: e1 along x1 - x0, e2 in the plane, orthogonal to it. */
ATS_FN ats_membrane_rest ats_membrane_rest_of(const ats_vec3 x_rest[3]) {
  const ats_vec3 d1 = ats_sub(x_rest[1], x_rest[0]);
  const ats_vec3 d2 = ats_sub(x_rest[2], x_rest[0]);
  const ats_real l1 = ats_length(d1);
  const ats_real u2 = ats_dot(d2, d1) / l1;                  /* e1 . d2 */
  const ats_real v2 = ats_length(ats_v3_cross(d1, d2)) / l1; /* e2 . d2 > 0 */
  /* Dm = [[l1, u2], [0, v2]] */
  ats_membrane_rest r;
  r.dm_inv.a00 = (ats_real)1 / l1;
  r.dm_inv.a01 = -u2 / (l1 * v2);
  r.dm_inv.a10 = 0;
  r.dm_inv.a11 = (ats_real)1 / v2;
  r.area = (ats_real)0.5 * l1 * v2;
  return r;
}

ATS_FN ats_vec2 ats_membrane_shape_vector(ats_mat2 dm_inv, int a) {
  ats_vec2 b;
  if (a == 0) {
    b.x = -(dm_inv.a00 + dm_inv.a10);
    b.y = -(dm_inv.a01 + dm_inv.a11);
  } else if (a == 1) {
    b.x = dm_inv.a00;
    b.y = dm_inv.a01;
  } else {
    b.x = dm_inv.a10;
    b.y = dm_inv.a11;
  }
  return b;
}

ATS_FN ats_mat32 ats_membrane_deformation(const ats_vec3 x[3], ats_mat2 dm_inv) {
  const ats_vec3 d1 = ats_sub(x[1], x[0]);
  const ats_vec3 d2 = ats_sub(x[2], x[0]);
  ats_mat32 f;
  f.c[0] = ats_add(ats_scale(d1, dm_inv.a00), ats_scale(d2, dm_inv.a10));
  f.c[1] = ats_add(ats_scale(d1, dm_inv.a01), ats_scale(d2, dm_inv.a11));
  return f;
}

/* F v (v in R^2) */
ATS_FN ats_vec3 ats_m32_mul_v(ats_mat32 f, ats_vec2 v) {
  return ats_add(ats_scale(f.c[0], v.x), ats_scale(f.c[1], v.y));
}

/* Green strain (symmetric: a01 == a10). */
ATS_FN ats_mat2 ats_membrane_green_strain(ats_mat32 f) {
  ats_mat2 e;
  e.a00 = (ats_real)0.5 * (ats_dot(f.c[0], f.c[0]) - 1);
  e.a01 = (ats_real)0.5 * ats_dot(f.c[0], f.c[1]);
  e.a10 = e.a01;
  e.a11 = (ats_real)0.5 * (ats_dot(f.c[1], f.c[1]) - 1);
  return e;
}

ATS_FN ats_mat2 ats_membrane_stvk_pk2(ats_mat32 f, ats_real mu, ats_real lambda) {
  const ats_mat2 e = ats_membrane_green_strain(f);
  const ats_real lt = lambda * (e.a00 + e.a11);
  ats_mat2 s;
  s.a00 = 2 * mu * e.a00 + lt;
  s.a01 = 2 * mu * e.a01;
  s.a10 = s.a01;
  s.a11 = 2 * mu * e.a11 + lt;
  return s;
}

ATS_FN ats_real ats_membrane_stvk_energy_density(ats_mat32 f, ats_real mu, ats_real lambda) {
  const ats_mat2 e = ats_membrane_green_strain(f);
  const ats_real tr = e.a00 + e.a11;
  return mu * (e.a00 * e.a00 + 2 * e.a01 * e.a01 + e.a11 * e.a11) + (ats_real)0.5 * lambda * tr * tr;
}

ATS_FN ats_real ats_membrane_stvk_energy(const ats_vec3 x[3], ats_mat2 dm_inv, ats_real area, ats_real mu,
                                         ats_real lambda) {
  return area * ats_membrane_stvk_energy_density(ats_membrane_deformation(x, dm_inv), mu, lambda);
}

/* Gradient with respect to x[a]: A F (S b_a). */
ATS_FN ats_vec3 ats_membrane_stvk_gradient(const ats_vec3 x[3], ats_mat2 dm_inv, ats_real area, ats_real mu,
                                           ats_real lambda, int a) {
  const ats_mat32 f = ats_membrane_deformation(x, dm_inv);
  const ats_mat2 s = ats_membrane_stvk_pk2(f, mu, lambda);
  const ats_vec2 b = ats_membrane_shape_vector(dm_inv, a);
  ats_vec2 sb;
  sb.x = s.a00 * b.x + s.a01 * b.y;
  sb.y = s.a10 * b.x + s.a11 * b.y;
  return ats_scale(ats_m32_mul_v(f, sb), area);
}

/* The block H_ab = d^2 E / dx_a dx_b (H_ba = H_ab^T). */
ATS_FN ats_mat3 ats_membrane_stvk_hessian(const ats_vec3 x[3], ats_mat2 dm_inv, ats_real area, ats_real mu,
                                          ats_real lambda, int a, int b) {
  const ats_mat32 f = ats_membrane_deformation(x, dm_inv);
  const ats_mat2 s = ats_membrane_stvk_pk2(f, mu, lambda);
  const ats_vec2 ba = ats_membrane_shape_vector(dm_inv, a);
  const ats_vec2 bb = ats_membrane_shape_vector(dm_inv, b);
  const ats_vec3 ya = ats_m32_mul_v(f, ba);
  const ats_vec3 yb = ats_m32_mul_v(f, bb);
  const ats_real bsb = bb.x * (s.a00 * ba.x + s.a01 * ba.y) + bb.y * (s.a10 * ba.x + s.a11 * ba.y);
  const ats_mat3 fft = ats_m3_add(ats_m3_outer(f.c[0], f.c[0]), ats_m3_outer(f.c[1], f.c[1]));
  ats_mat3 h = ats_m3_diag(bsb);
  h = ats_m3_add(h, ats_m3_outer(yb, ats_scale(ya, mu)));
  h = ats_m3_add(h, ats_m3_scale(fft, mu * (ba.x * bb.x + ba.y * bb.y)));
  h = ats_m3_add(h, ats_m3_outer(ya, ats_scale(yb, lambda)));
  return ats_m3_scale(h, area);
}

/* H_aa with negative eigenvalues clamped at 0 (ats_m3_project_psd): the
 * (b^T S b) I term is negative under compression, as in wrinkling cloth. */
ATS_FN ats_mat3 ats_membrane_stvk_hessian_diag_psd(const ats_vec3 x[3], ats_mat2 dm_inv, ats_real area, ats_real mu,
                                                   ats_real lambda, int a) {
  return ats_m3_project_psd(ats_membrane_stvk_hessian(x, dm_inv, area, mu, lambda, a, a));
}

#endif
