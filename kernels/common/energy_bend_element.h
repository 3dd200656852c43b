/* One bending stencil's energy, gradient and Hessian blocks under its model
 * (common/element_types.h: ATS_BEND_ISOMETRIC or ATS_BEND_DIHEDRAL), for
 * every method and the double-precision reference. stiffness = 1/compliance;
 * `scale` is the stencil's scale (isometric: 3/(A0 + A1); dihedral:
 * 3/2 |e|^2/(A0 + A1), so the dihedral stiffness is scale * stiffness). The
 * isometric model is zero only for a flat rest shape; the dihedral one is
 * zero at any rest angle (a curved rest shape keeps its shape). */
#ifndef ATS_ENERGY_BEND_ELEMENT_H
#define ATS_ENERGY_BEND_ELEMENT_H

#include "common/energy_bending.h"
#include "common/energy_dihedral.h"

#ifndef ATS_BEND_ISOMETRIC
#define ATS_BEND_ISOMETRIC 0
#define ATS_BEND_DIHEDRAL 1
#endif

ATS_FN ats_real ats_bend_element_energy(int model, const ats_vec3 x[4], const ats_real K[4], ats_real scale,
                                        ats_real stiffness, ats_real rest_angle) {
  if (model == ATS_BEND_DIHEDRAL) return ats_dihedral_energy(x, rest_angle, scale * stiffness);
  return ats_bend_energy(x, K, scale, stiffness);
}

/* Gradient with respect to x[a]. */
ATS_FN ats_vec3 ats_bend_element_gradient(int model, const ats_vec3 x[4], const ats_real K[4], ats_real scale,
                                          ats_real stiffness, ats_real rest_angle, int a) {
  if (model == ATS_BEND_DIHEDRAL) return ats_dihedral_gradient(x, rest_angle, scale * stiffness, a);
  return ats_bend_gradient(x, K, scale, stiffness, a);
}

/* The block H_ab, PSD as a whole element: the isometric one is constant,
 * the dihedral one is its Gauss-Newton part (exact at the rest angle). */
ATS_FN ats_mat3 ats_bend_element_hessian(int model, const ats_vec3 x[4], const ats_real K[4], ats_real scale,
                                         ats_real stiffness, int a, int b) {
  if (model == ATS_BEND_DIHEDRAL) return ats_dihedral_hessian_gn(x, scale * stiffness, a, b);
  return ats_bend_hessian(K, scale, stiffness, a, b);
}

#endif
