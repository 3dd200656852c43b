/* Energy of an XPBD distance constraint C = |xa - xb| - L with compliance
 * alpha (Macklin et al. 2016, Eq. 4: U = 1/2 C alpha^-1 C), k = 1/alpha:
 *   E = 1/2 k c^2,   d = xa - xb, l = |d|, n = d / l, c = l - L,
 *   grad_a E = k c n = -grad_b E,
 *   H_aa = H_bb = -H_ab = -H_ba = k [ n n^T + f (I - n n^T) ],  f = c / l = 1 - L/l.
 * H_aa has eigenvalue k along n and k f (twice) across it; f < 0 when the
 * spring is compressed, so the PSD projection clamps f at 0 (Choi & Ko 2002),
 * which makes the 6x6 element Hessian [[H, -H], [-H, H]] PSD.
 * A zero-length spring has no direction: energy 1/2 k L^2 with zero gradient
 * and zero Hessian, finite rather than NaN. */
#ifndef ATS_ENERGY_STRETCH_H
#define ATS_ENERGY_STRETCH_H

#include "common/ats_math.h"
#include "common/energy_mat3.h"

/* Below this length the spring direction is undefined. */
#define ATS_STRETCH_MIN_LENGTH ((ats_real)1e-20)

/* Error-free transforms (Ogita, Rump & Oishi 2005): a*b = p + e exactly,
 * a + b = s + e exactly. They need IEEE arithmetic as written: no fast-math
 * reassociation, and no contraction of a product into a later sum (the
 * kernel program turns FP_CONTRACT off, the host files -ffp-contract=off). */
ATS_FN ats_real ats_two_product(ats_real a, ats_real b, ats_real* e) {
  const ats_real p = a * b;
  *e = ATS_FMA(a, b, -p);
  return p;
}
ATS_FN ats_real ats_two_sum(ats_real a, ats_real b, ats_real* e) {
  const ats_real s = a + b;
  const ats_real z = s - a;
  *e = (a - (s - z)) + (b - z);
  return s;
}

/* Adds a*a to the double-length sum (s, err) (Dot2, Ogita et al. 2005). */
ATS_FN ats_real ats_add_square(ats_real s, ats_real a, ats_real* err) {
  ats_real e_prod = 0, e_sum = 0;
  const ats_real p = ats_two_product(a, a, &e_prod);
  s = ats_two_sum(s, p, &e_sum);
  *err += e_prod + e_sum;
  return s;
}

/* c = l - L, accurate relative to c itself. Stiff springs sit near their
 * rest length, where l - L cancels: in float, l carries an error of about
 * one ulp of l (and d = xa - xb one ulp of d when xa, xb differ in sign),
 * as large as c itself at strains near 1e-6. So c is taken as
 * (|d|^2 - L^2) / (l + L) with d kept exact as d + delta and the numerator
 * summed in twice the working precision (Dot2, Ogita et al. 2005): the float
 * kernels then agree with the double reference to a few ulps of c. */
ATS_FN ats_real ats_stretch_extension(ats_vec3 xa, ats_vec3 xb, ats_real rest, ats_real l) {
  if (l + rest <= 0) return 0;
  ats_real err = 0, dx = 0, dy = 0, dz = 0;
  const ats_real ax = ats_two_sum(xa.x, -xb.x, &dx);
  const ats_real ay = ats_two_sum(xa.y, -xb.y, &dy);
  const ats_real az = ats_two_sum(xa.z, -xb.z, &dz);
  ats_real s = ats_add_square(0, ax, &err);
  s = ats_add_square(s, ay, &err);
  s = ats_add_square(s, az, &err);
  /* -L^2 */
  ats_real e_prod = 0, e_sum = 0;
  s = ats_two_sum(s, ats_two_product(rest, -rest, &e_prod), &e_sum);
  err += e_prod + e_sum;
  /* |a + delta|^2 = |a|^2 + 2 a.delta + |delta|^2; the last is below rounding. */
  err += 2 * (ax * dx + ay * dy + az * dz);
  return (s + err) / (l + rest);
}

ATS_FN ats_real ats_stretch_energy(ats_vec3 xa, ats_vec3 xb, ats_real rest, ats_real stiffness) {
  const ats_real c = ats_stretch_extension(xa, xb, rest, ats_length(ats_sub(xa, xb)));
  return (ats_real)0.5 * stiffness * c * c;
}

/* Gradient with respect to xa; the one with respect to xb is its negative. */
ATS_FN ats_vec3 ats_stretch_gradient(ats_vec3 xa, ats_vec3 xb, ats_real rest, ats_real stiffness) {
  const ats_vec3 d = ats_sub(xa, xb);
  const ats_real l = ats_length(d);
  if (l <= ATS_STRETCH_MIN_LENGTH) return ats_v3(0, 0, 0);
  return ats_scale(d, stiffness * ats_stretch_extension(xa, xb, rest, l) / l);
}

/* The block H_aa (= H_bb = -H_ab); project_psd != 0 clamps f = c/l at 0. */
ATS_FN ats_mat3 ats_stretch_hessian(ats_vec3 xa, ats_vec3 xb, ats_real rest, ats_real stiffness, int project_psd) {
  const ats_vec3 d = ats_sub(xa, xb);
  const ats_real l = ats_length(d);
  if (l <= ATS_STRETCH_MIN_LENGTH) return ats_m3_diag(0);
  const ats_vec3 n = ats_scale(d, (ats_real)1 / l);
  ats_real f = ats_stretch_extension(xa, xb, rest, l) / l;
  if (project_psd && f < 0) f = 0;
  /* k [ (1 - f) n n^T + f I ] */
  return ats_m3_add(ats_m3_outer(n, ats_scale(n, stiffness * ((ats_real)1 - f))), ats_m3_diag(stiffness * f));
}

#endif
