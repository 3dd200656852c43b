/* Material damping along a spring (issue #13): Rayleigh stiffness-
 * proportional damping, coefficient c = beta k (N s/m) for a spring of
 * stiffness k and the scene's `damping: beta` (s).
 *
 * Explicit integration takes the force itself, on particle a
 *   f_a = c ((v_b - v_a) . n) n,  n = (x_a - x_b)/|x_a - x_b|,  f_b = -f_a,
 * which removes energy at the rate c ((v_a - v_b) . n)^2 and nothing else.
 *
 * The implicit methods take it at the end-of-substep velocity
 * v = (x - x_t)/h with the direction n_t fixed at the substep's start x_t,
 * as the quadratic term of the incremental potential
 *   D(x) = 1/2 (c/h) (n_t . (dx_a - dx_b))^2,  dx = x - x_t,
 *   grad_a D = (c/h) s n_t = -grad_b D,  s = n_t . (dx_a - dx_b),
 *   H_aa = H_bb = -H_ab = (c/h) n_t n_t^T (PSD),
 * whose gradient is minus that force at v = dx/h: a minimiser of E + D is
 * an implicit-Euler step with the damping force (as air drag, sim_layout.hpp).
 * A zero-length spring has no direction and no damping. */
#ifndef ATS_ENERGY_SPRING_DAMPING_H
#define ATS_ENERGY_SPRING_DAMPING_H

#include "common/ats_math.h"
#include "common/energy_mat3.h"

/* The unit direction a -> from b; (0, 0, 0) below the stretch minimum length. */
ATS_FN ats_vec3 ats_spring_direction(ats_vec3 xa, ats_vec3 xb) {
  const ats_vec3 d = ats_sub(xa, xb);
  const ats_real l = ats_length(d);
  if (l <= (ats_real)1e-20) return ats_v3(0, 0, 0);
  return ats_scale(d, (ats_real)1 / l);
}

/* Explicit: the damping force on a (b gets its negation); c in N s/m. */
ATS_FN ats_vec3 ats_spring_damping_force(ats_vec3 xa, ats_vec3 xb, ats_vec3 va, ats_vec3 vb, ats_real c) {
  const ats_vec3 n = ats_spring_direction(xa, xb);
  return ats_scale(n, c * ats_dot(ats_sub(vb, va), n));
}

/* Implicit: D, grad_a D and H_aa for c_over_h = c/h, n_t from the start
 * positions xa0, xb0. */
ATS_FN ats_real ats_spring_damping_energy(ats_vec3 xa, ats_vec3 xb, ats_vec3 xa0, ats_vec3 xb0, ats_real c_over_h) {
  const ats_vec3 n = ats_spring_direction(xa0, xb0);
  const ats_real s = ats_dot(n, ats_sub(ats_sub(xa, xa0), ats_sub(xb, xb0)));
  return (ats_real)0.5 * c_over_h * s * s;
}

ATS_FN ats_vec3 ats_spring_damping_gradient(ats_vec3 xa, ats_vec3 xb, ats_vec3 xa0, ats_vec3 xb0, ats_real c_over_h) {
  const ats_vec3 n = ats_spring_direction(xa0, xb0);
  const ats_real s = ats_dot(n, ats_sub(ats_sub(xa, xa0), ats_sub(xb, xb0)));
  return ats_scale(n, c_over_h * s);
}

ATS_FN ats_mat3 ats_spring_damping_hessian(ats_vec3 xa0, ats_vec3 xb0, ats_real c_over_h) {
  const ats_vec3 n = ats_spring_direction(xa0, xb0);
  return ats_m3_outer(n, ats_scale(n, c_over_h));
}

#endif
