/* Dihedral-angle bending of the two triangles at an interior edge, the
 * discrete-shells energy (Grinspun et al. 2003, "Discrete Shells"; Tamstorf
 * & Grinspun 2013, "Discrete bending forces and their Jacobians", Eq. 2):
 *   E = k (theta - theta_0)^2,   k = k_b |e0|^2 / (A0_a + A0_b),
 * with the edge length and the two triangle areas of the rest shape folded
 * into the stiffness k (ats_dihedral_rest_stiffness; Grinspun's factor 3 goes
 * into k_b). Stencil: x[0], x[1] the edge, x[2] the wing of triangle
 * (x0, x1, x2), x[3] the wing of triangle (x0, x3, x1); with the area normals
 *   e = x1 - x0,  n_a = e x (x2 - x0),  n_b = (x3 - x0) x e,
 * theta = atan2(e/|e| . (n_b x n_a), n_a . n_b) in (-pi, pi], 0 when flat,
 * positive when the wings fold towards their normals. Its gradient (Bridson,
 * Marino & Fedkiw 2003, "Simulation of clothing with folds and wrinkles", §4):
 *   dtheta/dx2 = |e| n_a / |n_a|^2,  dtheta/dx3 = |e| n_b / |n_b|^2,
 *   dtheta/dx0 = (t2 - 1) dtheta/dx2 + (t3 - 1) dtheta/dx3,
 *   dtheta/dx1 = -t2 dtheta/dx2 - t3 dtheta/dx3,  t_i = (x_i - x0).e / |e|^2.
 * Hessian: the Gauss-Newton part H_ab = 2 k (dtheta/dx_a)(dtheta/dx_b)^T only,
 * PSD by construction; the dropped term 2 k (theta - theta_0) d2theta/dx2
 * vanishes at the rest angle (the full one: Tamstorf & Grinspun 2013, §4).
 * A degenerate triangle or edge (zero normal or length) has no angle
 * gradient: gradient and Hessian are 0 there, finite rather than NaN.
 * theta jumps by 2 pi when a wing passes through the other triangle. */
#ifndef ATS_ENERGY_DIHEDRAL_H
#define ATS_ENERGY_DIHEDRAL_H

#include "common/ats_math.h"
#include "common/energy_mat3.h"

ATS_FN ats_real ats_dihedral_angle(const ats_vec3 x[4]) {
  const ats_vec3 e = ats_sub(x[1], x[0]);
  const ats_vec3 na = ats_v3_cross(e, ats_sub(x[2], x[0]));
  const ats_vec3 nb = ats_v3_cross(ats_sub(x[3], x[0]), e);
  const ats_real le = ats_length(e);
  if (!(le > 0)) return 0;
  return atan2(ats_dot(ats_v3_cross(nb, na), e) / le, ats_dot(na, nb));
}

/* dtheta/dx_a. */
ATS_FN ats_vec3 ats_dihedral_angle_gradient(const ats_vec3 x[4], int a) {
  const ats_vec3 e = ats_sub(x[1], x[0]);
  const ats_vec3 na = ats_v3_cross(e, ats_sub(x[2], x[0]));
  const ats_vec3 nb = ats_v3_cross(ats_sub(x[3], x[0]), e);
  const ats_real le2 = ats_dot(e, e), na2 = ats_dot(na, na), nb2 = ats_dot(nb, nb);
  if (!(le2 > 0 && na2 > 0 && nb2 > 0)) return ats_v3(0, 0, 0);
  const ats_real le = ATS_SQRT(le2);
  const ats_vec3 g2 = ats_scale(na, le / na2);
  const ats_vec3 g3 = ats_scale(nb, le / nb2);
  if (a == 2) return g2;
  if (a == 3) return g3;
  const ats_real t2 = ats_dot(ats_sub(x[2], x[0]), e) / le2;
  const ats_real t3 = ats_dot(ats_sub(x[3], x[0]), e) / le2;
  if (a == 0) return ats_add(ats_scale(g2, t2 - 1), ats_scale(g3, t3 - 1));
  return ats_scale(ats_add(ats_scale(g2, t2), ats_scale(g3, t3)), (ats_real)-1);
}

/* k = k_b |e|^2 / (A_a + A_b) of the rest stencil. */
ATS_FN ats_real ats_dihedral_rest_stiffness(const ats_vec3 x_rest[4], ats_real k_bend) {
  const ats_vec3 e = ats_sub(x_rest[1], x_rest[0]);
  const ats_real area = (ats_real)0.5 * (ats_length(ats_v3_cross(e, ats_sub(x_rest[2], x_rest[0]))) +
                                         ats_length(ats_v3_cross(ats_sub(x_rest[3], x_rest[0]), e)));
  return k_bend * ats_dot(e, e) / area;
}

ATS_FN ats_real ats_dihedral_energy(const ats_vec3 x[4], ats_real rest_angle, ats_real stiffness) {
  const ats_real d = ats_dihedral_angle(x) - rest_angle;
  return stiffness * d * d;
}

/* Gradient with respect to x[a]: 2 k (theta - theta_0) dtheta/dx_a. */
ATS_FN ats_vec3 ats_dihedral_gradient(const ats_vec3 x[4], ats_real rest_angle, ats_real stiffness, int a) {
  return ats_scale(ats_dihedral_angle_gradient(x, a), 2 * stiffness * (ats_dihedral_angle(x) - rest_angle));
}

/* Gauss-Newton block H_ab = 2 k (dtheta/dx_a)(dtheta/dx_b)^T (PSD; exact where
 * theta = theta_0). Its diagonal blocks are what vertex block descent needs. */
ATS_FN ats_mat3 ats_dihedral_hessian_gn(const ats_vec3 x[4], ats_real stiffness, int a, int b) {
  return ats_m3_outer(ats_dihedral_angle_gradient(x, a), ats_scale(ats_dihedral_angle_gradient(x, b), 2 * stiffness));
}

#endif
