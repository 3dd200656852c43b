/* Predict and velocity update of the implicit-Euler substep, shared by every
 * method: predict keeps x_t (for the velocity) and, for the methods that
 * minimise the incremental potential directly (VBD, JPGD), x~ = x_t + h v +
 * h^2 g (the inertia target, also the first guess). Pinned particles (w = 0)
 * stay. */
#include "common/particle_step.h"
#include "common/task.h"
/* Particle i's predict (common/particle_step.h); returns its new position. */
static inline float4 predict_particle(int i, __global float4* x, __global float4* v, __global float4* x_prev, float dt,
                                      float gx, float gy, float gz, float damp) {
  const float4 p = x[i];
  x_prev[i] = p;
  const ats_particle_state s = ats_predicted(p, v[i], dt, gx, gy, gz, damp);
  v[i] = s.v;
  x[i] = s.x;
  return s.x;
}

ATS_TASK void particles_predict(int i, __global float4* x, __global float4* v, __global float4* x_prev,
                                __global float4* x_tilde, float dt, float gx, float gy, float gz, float damp) {
  x_tilde[i] = predict_particle(i, x, v, x_prev, dt, gx, gy, gz, damp);
}

ATS_TASK void particles_update_velocity(int i, __global const float4* x, __global float4* v,
                                        __global const float4* x_prev, float inv_dt) {
  v[i] = ats_velocity_update(x[i], x_prev[i], inv_dt);
}

/* The ground plane y = height (common/particle_step.h). */
ATS_TASK void particles_ground(int i, __global float4* x, float height) { x[i] = ats_above_ground(x[i], height); }

/* Copies positions (used where an iteration leaves its result elsewhere). */
ATS_TASK void particles_copy(int i, __global float4* dst, __global const float4* src) { dst[i] = src[i]; }
