/* The per-particle time steps every method shares, on values: predict, the
 * ground projection and the velocity update of the implicit-Euler substep,
 * and the explicit integrators' updates. The kernels (common/particle_steps.cl,
 * explicit/explicit.cl) and the host references (solver/xpbd, vbd and
 * explicit) call these, so both run the same arithmetic in the same order
 * (DESIGN.md: one truth for the math). Pinned particles (w = 0) keep their
 * position and have v = 0.
 *
 * ats_float4 is OpenCL's float4 in kernels; host code defines it first as its
 * own 16-byte x, y, z, w struct (solver::Float4). */
#ifndef ATS_PARTICLE_STEP_H
#define ATS_PARTICLE_STEP_H

#include "common/ats_math.h"

ATS_FN ats_float4 ats_f4(float x, float y, float z, float w) {
  ats_float4 r;
  r.x = x;
  r.y = y;
  r.z = z;
  r.w = w;
  return r;
}

/* A particle's position and velocity after a step. */
typedef struct {
  ats_float4 x;
  ats_float4 v;
} ats_particle_state;

/* Semi-implicit Euler under gravity: v = (v + dt g) damp, x += dt v.
 * damp = 1/(1 + c dt) takes air drag c implicitly (solver/layout/
 * sim_layout.hpp); 1 without drag (exact: the same bits). The implicit
 * methods' predict: x~ = x_t + h v + h² g. */
ATS_FN ats_particle_state ats_predicted(ats_float4 p, ats_float4 vel, float dt, float gx, float gy, float gz,
                                        float damp) {
  ats_particle_state s;
  if (p.w == 0.0f) {
    s.x = p;
    s.v = ats_f4(0.0f, 0.0f, 0.0f, 0.0f);
    return s;
  }
  vel.x += dt * gx;
  vel.y += dt * gy;
  vel.z += dt * gz;
  vel.x *= damp;
  vel.y *= damp;
  vel.z *= damp;
  s.v = vel;
  s.x = ats_f4(p.x + dt * vel.x, p.y + dt * vel.y, p.z + dt * vel.z, p.w);
  return s;
}

/* The ground plane y = height: a free particle below it is put back on it
 * (the velocity update then removes the motion into the ground; no friction). */
ATS_FN ats_float4 ats_above_ground(ats_float4 p, float height) {
  if (p.w > 0.0f && p.y < height) return ats_f4(p.x, height, p.z, p.w);
  return p;
}

/* v = (x − x_t) / h, with the plan's 1/h (each method rounds it its own way:
 * the reference passes what the method's plan passes). */
ATS_FN ats_float4 ats_velocity_update(ats_float4 x, ats_float4 x_prev, float inv_dt) {
  return ats_f4((x.x - x_prev.x) * inv_dt, (x.y - x_prev.y) * inv_dt, (x.z - x_prev.z) * inv_dt, 0.0f);
}

/* Semi-implicit (symplectic) Euler on the forces, seed 001 Eq. 2:
 * v += h a(x, v), x += h v. */
ATS_FN ats_particle_state ats_semi_euler(ats_float4 p, ats_float4 vel, ats_float4 acc, float h) {
  ats_particle_state s;
  if (p.w == 0.0f) {
    s.x = p;
    s.v = ats_f4(0.0f, 0.0f, 0.0f, 0.0f);
    return s;
  }
  vel.x += h * acc.x;
  vel.y += h * acc.y;
  vel.z += h * acc.z;
  s.v = vel;
  s.x = ats_f4(p.x + h * vel.x, p.y + h * vel.y, p.z + h * vel.z, p.w);
  return s;
}

/* One explicit Runge-Kutta stage (midpoint Eq. 3, RK4 Eq. 4) on the state
 * (p, vel) at the step's start, with this stage's slopes k_x, k_v: the sums
 * (sx, sv) gain weight · slopes (pass zeros on the first stage), and the next
 * stage's state is (p, vel) + c_h (k_x, k_v). */
typedef struct {
  ats_float4 sum_x, sum_v; /* the weighted slopes so far */
  ats_float4 xs, vs;       /* the next stage's state */
} ats_rk_stage_state;

ATS_FN ats_rk_stage_state ats_rk_stage(ats_float4 p, ats_float4 vel, ats_float4 kx, ats_float4 kv, ats_float4 sx,
                                       ats_float4 sv, float weight, float c_h) {
  ats_rk_stage_state s;
  s.sum_x = ats_f4(sx.x + weight * kx.x, sx.y + weight * kx.y, sx.z + weight * kx.z, 0.0f);
  s.sum_v = ats_f4(sv.x + weight * kv.x, sv.y + weight * kv.y, sv.z + weight * kv.z, 0.0f);
  s.xs = ats_f4(p.x + c_h * kx.x, p.y + c_h * kx.y, p.z + c_h * kx.z, p.w);
  s.vs = ats_f4(vel.x + c_h * kv.x, vel.y + c_h * kv.y, vel.z + c_h * kv.z, 0.0f);
  return s;
}

/* The last stage: its slopes join the sums with `weight`, then
 * x += h_sum sum_x, v += h_sum sum_v (h_sum = h / total weight). */
ATS_FN ats_particle_state ats_rk_finish(ats_float4 p, ats_float4 vel, ats_float4 kx, ats_float4 kv, ats_float4 sx,
                                        ats_float4 sv, float weight, float h_sum) {
  ats_particle_state s;
  if (p.w == 0.0f) {
    s.x = p;
    s.v = ats_f4(0.0f, 0.0f, 0.0f, 0.0f);
    return s;
  }
  s.x = ats_f4(p.x + h_sum * (sx.x + weight * kx.x), p.y + h_sum * (sx.y + weight * kx.y),
               p.z + h_sum * (sx.z + weight * kx.z), p.w);
  s.v = ats_f4(vel.x + h_sum * (sv.x + weight * kv.x), vel.y + h_sum * (sv.y + weight * kv.y),
               vel.z + h_sum * (sv.z + weight * kv.z), 0.0f);
  return s;
}

#endif
