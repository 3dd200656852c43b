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
  ATS_UNROLL for (int i = 0; i < 3; ++i) a.r[i] = ats_add(a.r[i], b.r[i]);
  return a;
}

ATS_FN ats_mat3 ats_m3_scale(ats_mat3 a, ats_real s) {
  ATS_UNROLL for (int i = 0; i < 3; ++i) a.r[i] = ats_scale(a.r[i], s);
  return a;
}

/* --- Additions for the solid and shell materials (energy_tet_*.h,
 * energy_membrane_stvk.h, energy_dihedral.h). --- */

ATS_FN ats_vec3 ats_v3_cross(ats_vec3 a, ats_vec3 b) {
  return ats_v3(a.y * b.z - a.z * b.y, a.z * b.x - a.x * b.z, a.x * b.y - a.y * b.x);
}

ATS_FN ats_mat3 ats_m3_sub(ats_mat3 a, ats_mat3 b) {
  ATS_UNROLL for (int i = 0; i < 3; ++i) a.r[i] = ats_sub(a.r[i], b.r[i]);
  return a;
}

ATS_FN ats_mat3 ats_m3_transpose(ats_mat3 a) {
  ats_mat3 t;
  t.r[0] = ats_v3(a.r[0].x, a.r[1].x, a.r[2].x);
  t.r[1] = ats_v3(a.r[0].y, a.r[1].y, a.r[2].y);
  t.r[2] = ats_v3(a.r[0].z, a.r[1].z, a.r[2].z);
  return t;
}

/* a v */
ATS_FN ats_vec3 ats_m3_mul_v(ats_mat3 a, ats_vec3 v) {
  return ats_v3(ats_dot(a.r[0], v), ats_dot(a.r[1], v), ats_dot(a.r[2], v));
}

/* a b */
ATS_FN ats_mat3 ats_m3_mul(ats_mat3 a, ats_mat3 b) {
  const ats_mat3 bt = ats_m3_transpose(b);
  ats_mat3 m;
  ATS_UNROLL for (int i = 0; i < 3; ++i) m.r[i] = ats_m3_mul_v(bt, a.r[i]);
  return m;
}

ATS_FN ats_real ats_m3_trace(ats_mat3 a) { return a.r[0].x + a.r[1].y + a.r[2].z; }

/* Frobenius a : b */
ATS_FN ats_real ats_m3_ddot(ats_mat3 a, ats_mat3 b) {
  return ats_dot(a.r[0], b.r[0]) + ats_dot(a.r[1], b.r[1]) + ats_dot(a.r[2], b.r[2]);
}

/* Cofactor matrix: cof(a) = det(a) a^-T, defined for every a. Row i of
 * cof(a) is (row i+1) x (row i+2) of a. */
ATS_FN ats_mat3 ats_m3_cofactor(ats_mat3 a) {
  ats_mat3 c;
  c.r[0] = ats_v3_cross(a.r[1], a.r[2]);
  c.r[1] = ats_v3_cross(a.r[2], a.r[0]);
  c.r[2] = ats_v3_cross(a.r[0], a.r[1]);
  return c;
}

ATS_FN ats_real ats_m3_det(ats_mat3 a) { return ats_dot(a.r[0], ats_v3_cross(a.r[1], a.r[2])); }

/* [v]_x, the matrix of w -> v x w. */
ATS_FN ats_mat3 ats_m3_hat(ats_vec3 v) {
  ats_mat3 m;
  m.r[0] = ats_v3(0, -v.z, v.y);
  m.r[1] = ats_v3(v.z, 0, -v.x);
  m.r[2] = ats_v3(-v.y, v.x, 0);
  return m;
}

/* The nearest positive semi-definite matrix to the symmetric part of a (in
 * the Frobenius norm): eigen-decompose by cyclic Jacobi rotations
 * (Golub & Van Loan, Matrix Computations, 4th ed. §8.5; rotation as in
 * Numerical Recipes §11.1), clamp negative eigenvalues at 0, recompose.
 * Six sweeps bring a 3x3 to double rounding (convergence is quadratic); no
 * divisions by values that can be 0, so float and double both stay finite. */
#define ATS_JACOBI_SWEEPS 6
ATS_FN ats_mat3 ats_m3_project_psd(ats_mat3 m) {
  ats_real a[3][3], v[3][3];
  const ats_real row[3][3] = {
      {m.r[0].x, m.r[0].y, m.r[0].z}, {m.r[1].x, m.r[1].y, m.r[1].z}, {m.r[2].x, m.r[2].y, m.r[2].z}};
  ATS_UNROLL for (int i = 0; i < 3; ++i) {
    ATS_UNROLL for (int j = 0; j < 3; ++j) {
      a[i][j] = (ats_real)0.5 * (row[i][j] + row[j][i]);
      v[i][j] = i == j ? (ats_real)1 : (ats_real)0;
    }
  }
  ATS_UNROLL for (int sweep = 0; sweep < ATS_JACOBI_SWEEPS; ++sweep) {
    ATS_UNROLL for (int p = 0; p < 2; ++p) {
      ATS_UNROLL for (int q = p + 1; q < 3; ++q) {
        const ats_real apq = a[p][q];
        if (apq == 0) continue;
        /* t = tan of the rotation angle, the smaller root of t^2 + 2 theta t - 1 = 0 */
        const ats_real theta = (a[q][q] - a[p][p]) / (2 * apq);
        const ats_real abs_theta = theta < 0 ? -theta : theta;
        ats_real t = (ats_real)1 / (abs_theta + ATS_SQRT(theta * theta + 1)); /* 0 when theta^2 overflows */
        if (theta < 0) t = -t;
        const ats_real c = (ats_real)1 / ATS_SQRT(t * t + 1);
        const ats_real s = t * c;
        /* a <- J^T a J with J the rotation in the (p, q) plane */
        ATS_UNROLL for (int k = 0; k < 3; ++k) {
          const ats_real akp = a[k][p], akq = a[k][q];
          a[k][p] = c * akp - s * akq;
          a[k][q] = s * akp + c * akq;
        }
        ATS_UNROLL for (int k = 0; k < 3; ++k) {
          const ats_real apk = a[p][k], aqk = a[q][k];
          a[p][k] = c * apk - s * aqk;
          a[q][k] = s * apk + c * aqk;
        }
        a[p][q] = 0;
        a[q][p] = 0;
        ATS_UNROLL for (int k = 0; k < 3; ++k) {
          const ats_real vkp = v[k][p], vkq = v[k][q];
          v[k][p] = c * vkp - s * vkq;
          v[k][q] = s * vkp + c * vkq;
        }
      }
    }
  }
  /* sum over eigenpairs of max(lambda, 0) v v^T; the columns of v are the eigenvectors */
  ats_mat3 out = ats_m3_diag(0);
  ATS_UNROLL for (int e = 0; e < 3; ++e) {
    const ats_real l = a[e][e];
    if (l <= 0) continue;
    const ats_vec3 ve = ats_v3(v[0][e], v[1][e], v[2][e]);
    out = ats_m3_add(out, ats_m3_outer(ve, ats_scale(ve, l)));
  }
  return out;
}

#endif
