/* Explicit integration of mass-spring (and any elastic) models, seed 001
 * Eqs. 2-4: semi-implicit Euler, midpoint and RK4 on x' = v, v' = a(x, v).
 * Every task function works on one particle and reads only what the task
 * before wrote (the stage state), so any cut of a stage between devices
 * gives the one-device result bit for bit. Pinned particles (w = 0) keep
 * their position and have v = 0. */
#pragma OPENCL FP_CONTRACT OFF /* the stretch energy's error-free transforms */

#include "common/ats_math.h"
#include "common/task.h"
#include "common/vertex_force.h"
#include "common/particle_steps.cl"

/* accel[i] = g - c v + f/m at the stage state (xs, vs). */
ATS_TASK void explicit_forces(int i, __global const float4* xs, __global const float4* vs, __global float4* accel,
                              __global const int* adj_offsets, __global const int* adj,
                              __global const ats_distance_c* stretch, __global const ats_bend_c* bend,
                              __global const ats_tet_c* tets, float gx, float gy, float gz, float drag) {
  const ats_vec3 acc =
      particle_acceleration(i, xs, vs, adj_offsets, adj, stretch, bend, tets, ats_v3(gx, gy, gz), drag);
  accel[i] = (float4)(acc.x, acc.y, acc.z, 0.0f);
}

/* Semi-implicit (symplectic) Euler, Eq. 2: v += h a(x, v), x += h v. */
ATS_TASK void explicit_semi_euler(int i, __global float4* x, __global float4* v, __global const float4* accel,
                                  float h) {
  const float4 p = x[i];
  if (p.w == 0.0f) {
    v[i] = (float4)(0.0f);
    return;
  }
  const float4 acc = accel[i];
  float4 vel = v[i];
  vel.x += h * acc.x;
  vel.y += h * acc.y;
  vel.z += h * acc.z;
  v[i] = vel;
  x[i] = (float4)(p.x + h * vel.x, p.y + h * vel.y, p.z + h * vel.z, p.w);
}

/* One explicit Runge-Kutta stage (midpoint Eq. 3, RK4 Eq. 4) on the state
 * (x, v) at the step's start: this stage's slopes are k_x = vs, k_v = a;
 * the sums gain weight * slopes (reset on the first stage); the next stage
 * state is (x, v) + c h (k_x, k_v). */
ATS_TASK void explicit_stage(int i, __global const float4* x, __global const float4* v, __global float4* xs,
                             __global float4* vs, __global const float4* accel, __global float4* sum_x,
                             __global float4* sum_v, float weight, float c_h, int first) {
  const float4 p = x[i];
  const float4 kx = first ? v[i] : vs[i];
  const float4 kv = accel[i];
  const float4 sx = first ? (float4)(0.0f) : sum_x[i];
  const float4 sv = first ? (float4)(0.0f) : sum_v[i];
  sum_x[i] = (float4)(sx.x + weight * kx.x, sx.y + weight * kx.y, sx.z + weight * kx.z, 0.0f);
  sum_v[i] = (float4)(sv.x + weight * kv.x, sv.y + weight * kv.y, sv.z + weight * kv.z, 0.0f);
  const float4 vel = v[i];
  xs[i] = (float4)(p.x + c_h * kx.x, p.y + c_h * kx.y, p.z + c_h * kx.z, p.w);
  vs[i] = (float4)(vel.x + c_h * kv.x, vel.y + c_h * kv.y, vel.z + c_h * kv.z, 0.0f);
}

/* The last stage: its slopes join the sums with `weight`, then
 * x += h_sum sum_x, v += h_sum sum_v (h_sum = h / total weight). */
ATS_TASK void explicit_finish(int i, __global float4* x, __global float4* v, __global const float4* vs,
                              __global const float4* accel, __global const float4* sum_x, __global const float4* sum_v,
                              float weight, float h_sum) {
  const float4 p = x[i];
  if (p.w == 0.0f) {
    v[i] = (float4)(0.0f);
    return;
  }
  const float4 kx = vs[i], kv = accel[i], sx = sum_x[i], sv = sum_v[i];
  const float4 vel = v[i];
  x[i] = (float4)(p.x + h_sum * (sx.x + weight * kx.x), p.y + h_sum * (sx.y + weight * kx.y),
                  p.z + h_sum * (sx.z + weight * kx.z), p.w);
  v[i] = (float4)(vel.x + h_sum * (sv.x + weight * kv.x), vel.y + h_sum * (sv.y + weight * kv.y),
                  vel.z + h_sum * (sv.z + weight * kv.z), 0.0f);
}
