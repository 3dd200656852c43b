/* Isometric bending as an XPBD constraint. The energy of Bergou et al. 2006,
 * E = 1/2 k s |sum_i K_i x_i|^2, is E = 1/2 k |C|^2 for the vector constraint
 * C = sqrt(s) sum_i K_i x_i, which is linear in x: each component has
 * gradient sqrt(s) K_i per vertex and the XPBD update is exact in one step
 * when alone. Zero for a flat rest shape. */
#ifndef ATS_XPBD_BENDING_H
#define ATS_XPBD_BENDING_H

#include "common/ats_math.h"
#include "common/element_types.h"
#include "common/energy_dihedral.h"

typedef struct {
  ats_vec3 dx[4];
  ats_vec3 dlambda;
} ats_bend_step;

ATS_FN ats_vec3 ats_bend_curvature(const ats_vec3 x[4], const float K[4], float scale) {
  ats_vec3 c = ats_v3(0.0f, 0.0f, 0.0f);
  ATS_UNROLL for (int i = 0; i < 4; ++i) c = ats_add(c, ats_scale(x[i], K[i]));
  return ats_scale(c, ATS_SQRT(scale));
}

ATS_FN ats_bend_step ats_xpbd_bend(const ats_vec3 x[4], const float w[4], const float K[4], float scale,
                                   float compliance, ats_vec3 lambda, float dt) {
  ats_bend_step s;
  const float alpha = compliance / (dt * dt);
  float denom = alpha;
  ATS_UNROLL for (int i = 0; i < 4; ++i) denom += scale * w[i] * K[i] * K[i];
  const ats_vec3 c = ats_bend_curvature(x, K, scale);
  if (denom <= 0.0f) {
    s.dlambda = ats_v3(0.0f, 0.0f, 0.0f);
  } else {
    s.dlambda = ats_scale(ats_add(c, ats_scale(lambda, alpha)), -1.0f / denom);
  }
  const float root = ATS_SQRT(scale);
  ATS_UNROLL for (int i = 0; i < 4; ++i) s.dx[i] = ats_scale(s.dlambda, w[i] * root * K[i]);
  return s;
}

/* Dihedral bending as an XPBD constraint (curved rest shapes): the energy
 * k_d (theta - theta_0)^2, k_d = scale / compliance (common/element_types.h),
 * is 1/2 alpha_c^-1 C^2 for the scalar constraint C = theta - theta_0 with
 * alpha_c = compliance / (2 scale); one XPBD step on it (Macklin et al. 2016,
 * Eq. 18) with the angle gradient of common/energy_dihedral.h. The
 * multiplier is dlambda.x (y, z stay 0). */
ATS_FN ats_bend_step ats_xpbd_dihedral(const ats_vec3 x[4], const float w[4], float rest_angle, float scale,
                                       float compliance, float lambda, float dt) {
  ats_bend_step s;
  const float alpha = compliance / (2.0f * scale * dt * dt);
  ats_vec3 g[4];
  float denom = alpha;
  ATS_UNROLL for (int i = 0; i < 4; ++i) {
    g[i] = ats_dihedral_angle_gradient(x, i);
    denom += w[i] * ats_dot(g[i], g[i]);
  }
  const float c = ats_dihedral_angle(x) - rest_angle;
  const float dl = denom > 0.0f ? -(c + alpha * lambda) / denom : 0.0f;
  s.dlambda = ats_v3(dl, 0.0f, 0.0f);
  ATS_UNROLL for (int i = 0; i < 4; ++i) s.dx[i] = ats_scale(g[i], w[i] * dl);
  return s;
}

/* The step of a stencil under its model (ats_bend_c.model). */
ATS_FN ats_bend_step ats_xpbd_bend_element(const ats_vec3 x[4], const float w[4], const ats_bend_c* c, ats_vec3 lambda,
                                           float dt) {
  if (c->model == ATS_BEND_DIHEDRAL)
    return ats_xpbd_dihedral(x, w, c->rest_angle, c->scale, c->compliance, lambda.x, dt);
  return ats_xpbd_bend(x, w, c->K, c->scale, c->compliance, lambda, dt);
}

/* The XPBD residual C + alpha~ lambda of a stencil (3 components; the
 * dihedral one has only x). */
ATS_FN ats_vec3 ats_xpbd_bend_residual(const ats_vec3 x[4], const ats_bend_c* c, ats_vec3 lambda, float dt) {
  if (c->model == ATS_BEND_DIHEDRAL) {
    const float alpha = c->compliance / (2.0f * c->scale * dt * dt);
    return ats_v3(ats_dihedral_angle(x) - c->rest_angle + alpha * lambda.x, 0.0f, 0.0f);
  }
  const float alpha = c->compliance / (dt * dt);
  return ats_add(ats_bend_curvature(x, c->K, c->scale), ats_scale(lambda, alpha));
}

#endif
