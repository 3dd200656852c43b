/* Predict and velocity update of the implicit-Euler substep, shared by every
 * method: predict keeps x_t (for the velocity) and, for the methods that
 * minimise the incremental potential directly (VBD, JPGD), x~ = x_t + h v +
 * h^2 g (the inertia target, also the first guess). Pinned particles (w = 0)
 * stay. */
#include "common/task.h"
/* Semi-implicit Euler for particle i: v = (v + dt g) damp, x += dt v;
 * returns the new position (pinned particles keep theirs and lose their
 * velocity). damp = 1/(1 + c dt) takes air drag c implicitly
 * (solver/layout/sim_layout.hpp); 1 without drag (exact: same bits). */
static inline float4 predict_particle(int i, __global float4* x, __global float4* v, __global float4* x_prev, float dt,
                                      float gx, float gy, float gz, float damp) {
  const float4 p = x[i];
  x_prev[i] = p;
  if (p.w == 0.0f) {
    v[i] = (float4)(0.0f);
    return p;
  }
  float4 vel = v[i];
  vel.x += dt * gx;
  vel.y += dt * gy;
  vel.z += dt * gz;
  vel.x *= damp;
  vel.y *= damp;
  vel.z *= damp;
  v[i] = vel;
  const float4 q = (float4)(p.x + dt * vel.x, p.y + dt * vel.y, p.z + dt * vel.z, p.w);
  x[i] = q;
  return q;
}

ATS_TASK void particles_predict(int i, __global float4* x, __global float4* v, __global float4* x_prev,
                                __global float4* x_tilde, float dt, float gx, float gy, float gz, float damp) {
  x_tilde[i] = predict_particle(i, x, v, x_prev, dt, gx, gy, gz, damp);
}

ATS_TASK void particles_update_velocity(int i, __global const float4* x, __global float4* v,
                                        __global const float4* x_prev, float inv_dt) {
  const float4 d = x[i] - x_prev[i];
  v[i] = (float4)(d.x * inv_dt, d.y * inv_dt, d.z * inv_dt, 0.0f);
}

/* The ground plane y = height: a particle below it is put back on it (the
 * velocity update then removes the motion into the ground; no friction). */
ATS_TASK void particles_ground(int i, __global float4* x, float height) {
  const float4 p = x[i];
  if (p.w > 0.0f && p.y < height) x[i] = (float4)(p.x, height, p.z, p.w);
}

/* Copies positions (used where an iteration leaves its result elsewhere). */
ATS_TASK void particles_copy(int i, __global float4* dst, __global const float4* src) { dst[i] = src[i]; }
