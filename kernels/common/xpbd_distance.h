/* XPBD distance constraint C = |xa - xb| - rest (Macklin et al. 2016, Eq. 18):
 * dlambda = (-C - alpha~ lambda) / (wa + wb + alpha~), alpha~ = compliance/dt^2.
 * A stateless projection: positions in, corrections out. */
#ifndef ATS_XPBD_DISTANCE_H
#define ATS_XPBD_DISTANCE_H

#include "common/ats_math.h"

typedef struct {
  ats_vec3 dxa, dxb;
  float dlambda;
} ats_distance_step;

ATS_FN ats_distance_step ats_xpbd_distance(ats_vec3 xa, float wa, ats_vec3 xb, float wb, float rest, float compliance,
                                           float lambda, float dt) {
  ats_distance_step s;
  s.dxa = ats_v3(0.0f, 0.0f, 0.0f);
  s.dxb = s.dxa;
  s.dlambda = 0.0f;
  const float alpha = compliance / (dt * dt);
  const ats_vec3 d = ats_sub(xa, xb);
  const float len = ats_length(d);
  const float denom = wa + wb + alpha;
  if (len <= 1e-20f || denom <= 0.0f) return s;
  const float c = len - rest;
  s.dlambda = (-c - alpha * lambda) / denom;
  const ats_vec3 n = ats_scale(d, 1.0f / len);
  s.dxa = ats_scale(n, wa * s.dlambda);
  s.dxb = ats_scale(n, -wb * s.dlambda);
  return s;
}

/* With material damping (Macklin et al. 2016, Eq. 26): the damping
 * potential 1/2 (c/h) (grad C . (x - x0))^2 of common/energy_spring_damping.h
 * with c = beta k gives gamma = alpha c / h = beta / h (h the substep) and
 *   dlambda = (-C - alpha~ lambda - gamma grad C . ((xa - xa0) - (xb - xb0)))
 *             / ((1 + gamma)(wa + wb) + alpha~),
 * grad C = n at the current positions; gamma = 0 is the undamped step. */
ATS_FN ats_distance_step ats_xpbd_distance_damped(ats_vec3 xa, float wa, ats_vec3 xb, float wb, float rest,
                                                  float compliance, float lambda, float dt, ats_vec3 xa0, ats_vec3 xb0,
                                                  float gamma) {
  if (!(gamma > 0.0f)) return ats_xpbd_distance(xa, wa, xb, wb, rest, compliance, lambda, dt);
  ats_distance_step s;
  s.dxa = ats_v3(0.0f, 0.0f, 0.0f);
  s.dxb = s.dxa;
  s.dlambda = 0.0f;
  const float alpha = compliance / (dt * dt);
  const ats_vec3 d = ats_sub(xa, xb);
  const float len = ats_length(d);
  const float denom = (1.0f + gamma) * (wa + wb) + alpha;
  if (len <= 1e-20f || denom <= 0.0f) return s;
  const ats_vec3 n = ats_scale(d, 1.0f / len);
  const float moved = ats_dot(n, ats_sub(ats_sub(xa, xa0), ats_sub(xb, xb0)));
  s.dlambda = (-(len - rest) - alpha * lambda - gamma * moved) / denom;
  s.dxa = ats_scale(n, wa * s.dlambda);
  s.dxb = ats_scale(n, -wb * s.dlambda);
  return s;
}

/* The XPBD residual of one constraint, C(x) + alpha~ lambda (zero when solved). */
ATS_FN float ats_xpbd_distance_residual(ats_vec3 xa, ats_vec3 xb, float rest, float compliance, float lambda,
                                        float dt) {
  return ats_length(ats_sub(xa, xb)) - rest + compliance / (dt * dt) * lambda;
}

#endif
