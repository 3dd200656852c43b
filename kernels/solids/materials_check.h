/* One element of each material (common/energy_tet_neohookean.h,
 * energy_tet_stvk.h, energy_membrane_stvk.h, energy_dihedral.h) evaluated
 * from a flat array of inputs into a flat array of results. Shared by the
 * check kernel (solids/materials_check.cl) and its host test, so the same
 * math compiled by the OpenCL compiler and by the host compiler can be
 * compared value by value.
 * Inputs:  tet x[4], Dm^-1 (row-major), V, mu, lambda       (24 values)
 *          triangle x[3], Dm^-1 (2x2 row-major), A, mu, lambda (16)
 *          stencil x[4], rest angle, stiffness                (14)
 * Results: per material (neo-Hookean, StVK tet, StVK membrane, dihedral) a
 * record of ATS_MATERIALS_RECORD values: energy, gradient of each vertex
 * (4 x 3, zero past the triangle's 3), H_01 and the PSD diagonal block H_00
 * (row-major; the dihedral's are its Gauss-Newton blocks). */
#ifndef ATS_MATERIALS_CHECK_H
#define ATS_MATERIALS_CHECK_H

#include "common/ats_math.h"
#include "common/energy_dihedral.h"
#include "common/energy_mat3.h"
#include "common/energy_membrane_stvk.h"
#include "common/energy_tet_neohookean.h"
#include "common/energy_tet_stvk.h"

#define ATS_MATERIALS_IN 54
#define ATS_MATERIALS_RECORD 31
#define ATS_MATERIALS_OUT (4 * ATS_MATERIALS_RECORD)

ATS_FN ats_vec3 ats_materials_vec(const ats_real in[ATS_MATERIALS_IN], int at) {
  return ats_v3(in[at], in[at + 1], in[at + 2]);
}

ATS_FN void ats_materials_put_vec(ats_real out[ATS_MATERIALS_OUT], int at, ats_vec3 v) {
  out[at] = v.x;
  out[at + 1] = v.y;
  out[at + 2] = v.z;
}

ATS_FN void ats_materials_put_mat(ats_real out[ATS_MATERIALS_OUT], int at, ats_mat3 m) {
  for (int i = 0; i < 3; ++i) ats_materials_put_vec(out, at + 3 * i, m.r[i]);
}

ATS_FN void ats_materials_check(const ats_real in[ATS_MATERIALS_IN], ats_real out[ATS_MATERIALS_OUT]) {
  for (int i = 0; i < ATS_MATERIALS_OUT; ++i) out[i] = 0;
  ats_vec3 xt[4], xm[3], xd[4];
  for (int a = 0; a < 4; ++a) xt[a] = ats_materials_vec(in, 3 * a);
  ats_mat3 dm;
  for (int i = 0; i < 3; ++i) dm.r[i] = ats_materials_vec(in, 12 + 3 * i);
  const ats_real vol = in[21], mu_t = in[22], lambda_t = in[23];
  for (int a = 0; a < 3; ++a) xm[a] = ats_materials_vec(in, 24 + 3 * a);
  ats_mat2 dm2;
  dm2.a00 = in[33];
  dm2.a01 = in[34];
  dm2.a10 = in[35];
  dm2.a11 = in[36];
  const ats_real area = in[37], mu_m = in[38], lambda_m = in[39];
  for (int a = 0; a < 4; ++a) xd[a] = ats_materials_vec(in, 40 + 3 * a);
  const ats_real rest_angle = in[52], k_bend = in[53];

  int r = 0; /* neo-Hookean */
  out[r] = ats_tet_nh_energy(xt, dm, vol, mu_t, lambda_t);
  for (int a = 0; a < 4; ++a)
    ats_materials_put_vec(out, r + 1 + 3 * a, ats_tet_nh_gradient(xt, dm, vol, mu_t, lambda_t, a));
  ats_materials_put_mat(out, r + 13, ats_tet_nh_hessian(xt, dm, vol, mu_t, lambda_t, 0, 1));
  ats_materials_put_mat(out, r + 22, ats_tet_nh_hessian_diag_psd(xt, dm, vol, mu_t, lambda_t, 0));

  r += ATS_MATERIALS_RECORD; /* StVK tet */
  out[r] = ats_tet_stvk_energy(xt, dm, vol, mu_t, lambda_t);
  for (int a = 0; a < 4; ++a) {
    ats_materials_put_vec(out, r + 1 + 3 * a, ats_tet_stvk_gradient(xt, dm, vol, mu_t, lambda_t, a));
  }
  ats_materials_put_mat(out, r + 13, ats_tet_stvk_hessian(xt, dm, vol, mu_t, lambda_t, 0, 1));
  ats_materials_put_mat(out, r + 22, ats_tet_stvk_hessian_diag_psd(xt, dm, vol, mu_t, lambda_t, 0));

  r += ATS_MATERIALS_RECORD; /* StVK membrane */
  out[r] = ats_membrane_stvk_energy(xm, dm2, area, mu_m, lambda_m);
  for (int a = 0; a < 3; ++a) {
    ats_materials_put_vec(out, r + 1 + 3 * a, ats_membrane_stvk_gradient(xm, dm2, area, mu_m, lambda_m, a));
  }
  ats_materials_put_mat(out, r + 13, ats_membrane_stvk_hessian(xm, dm2, area, mu_m, lambda_m, 0, 1));
  ats_materials_put_mat(out, r + 22, ats_membrane_stvk_hessian_diag_psd(xm, dm2, area, mu_m, lambda_m, 0));

  r += ATS_MATERIALS_RECORD; /* dihedral */
  out[r] = ats_dihedral_energy(xd, rest_angle, k_bend);
  for (int a = 0; a < 4; ++a)
    ats_materials_put_vec(out, r + 1 + 3 * a, ats_dihedral_gradient(xd, rest_angle, k_bend, a));
  ats_materials_put_mat(out, r + 13, ats_dihedral_hessian_gn(xd, k_bend, 0, 1));
  ats_materials_put_mat(out, r + 22, ats_dihedral_hessian_gn(xd, k_bend, 0, 0));
}

#endif
