/* The 3x3 solve of vertex-block methods (VBD, Chen et al. 2024; block-
 * Jacobi preconditioned descent, Wang & Yang 2016): dx = H^-1 f for one
 * vertex, skipped when H is near singular. */
#ifndef ATS_VERTEX_SOLVE_H
#define ATS_VERTEX_SOLVE_H

#include "common/ats_math.h"
#include "common/energy_mat3.h"

typedef struct {
  ats_vec3 x;
  int ok; /* 0: |det H| too small relative to its scale, x = 0 */
} ats_solve3;

/* Cramer's rule through the adjugate, on H scaled by its largest entry so
 * that neither the determinant nor the singularity test can overflow (float
 * Hessians of stiff, strongly deformed elements reach 1e10 and more). */
ATS_FN ats_solve3 ats_m3_solve(ats_mat3 h, ats_vec3 b) {
  ats_solve3 s;
  s.x = ats_v3(0, 0, 0);
  s.ok = 0;
  ats_real m = 0;
  ATS_UNROLL for (int i = 0; i < 3; ++i) { m = fmax(m, fmax(fabs(h.r[i].x), fmax(fabs(h.r[i].y), fabs(h.r[i].z)))); }
  if (!(m > 0)) return s;
  const ats_real inv_m = (ats_real)1 / m;
  ATS_UNROLL for (int i = 0; i < 3; ++i) h.r[i] = ats_scale(h.r[i], inv_m);
  const ats_vec3 c0 = ats_v3_cross(h.r[1], h.r[2]);
  const ats_vec3 c1 = ats_v3_cross(h.r[2], h.r[0]);
  const ats_vec3 c2 = ats_v3_cross(h.r[0], h.r[1]);
  const ats_real det = ats_dot(h.r[0], c0);
  /* entries now lie in [-1, 1]: |det| below 1e-6 is singular in float */
  if (!(fabs(det) > (ats_real)1e-6)) return s;
  /* H^-1 b = adj(H/m) (b/m) / det(H/m); adj's columns are c0, c1, c2 */
  s.x = ats_scale(ats_add(ats_add(ats_scale(c0, b.x), ats_scale(c1, b.y)), ats_scale(c2, b.z)), inv_m / det);
  s.ok = 1;
  return s;
}

/* A vertex step d = H^-1 f that would cross the ground y = ground, redone
 * with y held at the ground: the 2x2 system in x, z of the same quadratic model with
 * dy = ground - y, so a vertex in contact takes the exact minimiser of its
 * block under the bound y >= ground (projecting the free step afterwards
 * would not: H couples y with x and z). */
ATS_FN ats_vec3 ats_vertex_step_above_ground(ats_mat3 h, ats_vec3 f, ats_vec3 d, ats_real y, ats_real ground) {
  const ats_real dy = ground - y;
  const ats_real bx = f.x - h.r[0].y * dy, bz = f.z - h.r[2].y * dy;
  const ats_real a = h.r[0].x, b = h.r[0].z, c = h.r[2].x, e = h.r[2].z;
  const ats_real det = a * e - b * c;
  const ats_real scale = fmax(fmax(fabs(a), fabs(e)), fmax(fabs(b), fabs(c)));
  if (!(fabs(det) > (ats_real)1e-6 * scale * scale)) return ats_v3(d.x, dy, d.z);
  return ats_v3((e * bx - b * bz) / det, dy, (a * bz - c * bx) / det);
}

#endif
