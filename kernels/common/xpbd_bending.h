/* Isometric bending as an XPBD constraint. The energy of Bergou et al. 2006,
 * E = 1/2 k s |sum_i K_i x_i|^2, is E = 1/2 k |C|^2 for the vector constraint
 * C = sqrt(s) sum_i K_i x_i, which is linear in x: each component has
 * gradient sqrt(s) K_i per vertex and the XPBD update is exact in one step
 * when alone. Zero for a flat rest shape. */
#ifndef ATS_XPBD_BENDING_H
#define ATS_XPBD_BENDING_H

#include "common/ats_math.h"

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

#endif
