/* Kinematics of a linear tetrahedron (Sifakis & Barbic 2012, "FEM
 * simulation of 3D deformable solids", SIGGRAPH course notes, §4.1-4.3):
 *   Ds = [x1 - x0, x2 - x0, x3 - x0],  F = Ds Dm^-1,
 * with Dm the same matrix of the rest positions. F is linear in the
 * positions, F = sum_a x_a b_a^T, where the shape vector b_a (a = 1, 2, 3)
 * is row a-1 of Dm^-1 and b_0 = -(b_1 + b_2 + b_3). So for an energy
 * V Psi(F) with first Piola-Kirchhoff stress P = dPsi/dF:
 *   grad_a = V P b_a,   (H_ab)_km = V sum_ln dP_kl/dF_mn (b_a)_l (b_b)_n.
 * The rest inverse Dm^-1 and the rest volume V = |det Dm| / 6 come from the
 * model; the energies here never divide, so an inverted or flat tet
 * (det F <= 0) stays finite. */
#ifndef ATS_TET_KINEMATICS_H
#define ATS_TET_KINEMATICS_H

#include "common/ats_math.h"
#include "common/energy_mat3.h"

/* F = Ds Dm^-1 = sum_{a=1..3} (x_a - x_0) b_a^T, from edge vectors so that a
 * translated element gives the same F in float. */
ATS_FN ats_mat3 ats_tet_deformation(const ats_vec3 x[4], ats_mat3 dm_inv) {
  const ats_mat3 ds_t = {{ats_sub(x[1], x[0]), ats_sub(x[2], x[0]), ats_sub(x[3], x[0])}}; /* Ds^T */
  return ats_m3_mul(ats_m3_transpose(ds_t), dm_inv);
}

/* b_a: dF/dx_a = I (x) b_a^T. */
ATS_FN ats_vec3 ats_tet_shape_vector(ats_mat3 dm_inv, int a) {
  if (a == 0) return ats_scale(ats_add(ats_add(dm_inv.r[0], dm_inv.r[1]), dm_inv.r[2]), (ats_real)-1);
  return dm_inv.r[a - 1];
}

/* The rest data of a tet from its rest positions: Dm^-1 and V = det Dm / 6
 * (negative for a tet given in inverted order; callers normally use |V|).
 * Dm^-1 = cof(Dm)^T / det Dm; a flat rest tet has none (its det is 0). */
typedef struct {
  ats_mat3 dm_inv;
  ats_real volume;
} ats_tet_rest;

ATS_FN ats_tet_rest ats_tet_rest_of(const ats_vec3 x_rest[4]) {
  const ats_mat3 dm_t = {{ats_sub(x_rest[1], x_rest[0]), ats_sub(x_rest[2], x_rest[0]), ats_sub(x_rest[3], x_rest[0])}};
  const ats_real det = ats_m3_det(dm_t);
  ats_tet_rest r;
  /* (Dm^T)^-1 = cof(Dm^T)^T / det, so Dm^-1 = cof(Dm^T) / det */
  r.dm_inv = ats_m3_scale(ats_m3_cofactor(dm_t), (ats_real)1 / det);
  r.volume = det / 6;
  return r;
}

/* Invariants of the displacement gradient G = F - I, without cancellation
 * near rest: J - 1 = det(I + G) - 1 = tr G + s2(G) + det G, with s2 the sum
 * of the principal 2x2 minors, and cof(I + G) - I = (tr G) I - G^T + cof G. */
ATS_FN ats_real ats_m3_minor_sum(ats_mat3 g) { return ats_m3_trace(ats_m3_cofactor(g)); }

ATS_FN ats_real ats_tet_volume_change(ats_mat3 g) { /* J - 1 */
  return ats_m3_trace(g) + ats_m3_minor_sum(g) + ats_m3_det(g);
}

#endif
