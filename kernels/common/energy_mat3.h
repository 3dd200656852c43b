/* 3x3 matrices for the per-vertex Hessian blocks of the element energies
 * (energy_*.h), in the scalar type ats_real of common/ats_math.h. */
#ifndef ATS_ENERGY_MAT3_H
#define ATS_ENERGY_MAT3_H

#include "common/ats_math.h"

/* Row-major: r[i] is row i. */
typedef struct {
  ats_vec3 r[3];
} ats_mat3;

/* s I */
ATS_FN ats_mat3 ats_m3_diag(ats_real s) {
  ats_mat3 m;
  m.r[0] = ats_v3(s, 0, 0);
  m.r[1] = ats_v3(0, s, 0);
  m.r[2] = ats_v3(0, 0, s);
  return m;
}

/* a b^T */
ATS_FN ats_mat3 ats_m3_outer(ats_vec3 a, ats_vec3 b) {
  ats_mat3 m;
  m.r[0] = ats_scale(b, a.x);
  m.r[1] = ats_scale(b, a.y);
  m.r[2] = ats_scale(b, a.z);
  return m;
}

ATS_FN ats_mat3 ats_m3_add(ats_mat3 a, ats_mat3 b) {
  for (int i = 0; i < 3; ++i) a.r[i] = ats_add(a.r[i], b.r[i]);
  return a;
}

ATS_FN ats_mat3 ats_m3_scale(ats_mat3 a, ats_real s) {
  for (int i = 0; i < 3; ++i) a.r[i] = ats_scale(a.r[i], s);
  return a;
}

#endif
