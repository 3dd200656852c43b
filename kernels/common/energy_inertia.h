/* Inertia term of the incremental potential that implicit Euler and
 * converged XPBD minimise (He et al. 2025 §3.1, Eq. 1), per particle:
 *   E = 1/2 h^-2 m |x - x~|^2,  grad E = h^-2 m (x - x~),  Hessian h^-2 m I.
 * inv_h2 = 1/h^2. Pinned particles are no variables: callers skip them. */
#ifndef ATS_ENERGY_INERTIA_H
#define ATS_ENERGY_INERTIA_H

#include "common/ats_math.h"
#include "common/energy_mat3.h"

ATS_FN ats_real ats_inertia_energy(ats_vec3 x, ats_vec3 x_tilde, ats_real mass, ats_real inv_h2) {
  const ats_vec3 d = ats_sub(x, x_tilde);
  return (ats_real)0.5 * mass * inv_h2 * ats_dot(d, d);
}

ATS_FN ats_vec3 ats_inertia_gradient(ats_vec3 x, ats_vec3 x_tilde, ats_real mass, ats_real inv_h2) {
  return ats_scale(ats_sub(x, x_tilde), mass * inv_h2);
}

ATS_FN ats_mat3 ats_inertia_hessian(ats_real mass, ats_real inv_h2) { return ats_m3_diag(mass * inv_h2); }

#endif
