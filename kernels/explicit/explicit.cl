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

/* Semi-implicit (symplectic) Euler, Eq. 2 (common/particle_step.h). */
ATS_TASK void explicit_semi_euler(int i, __global float4* x, __global float4* v, __global const float4* accel,
                                  float h) {
  const ats_particle_state s = ats_semi_euler(x[i], v[i], accel[i], h);
  x[i] = s.x;
  v[i] = s.v;
}

/* One explicit Runge-Kutta stage (common/particle_step.h): this stage's
 * slopes are k_x = vs (v on the first stage), k_v = a; the sums restart on
 * the first stage. */
ATS_TASK void explicit_stage(int i, __global const float4* x, __global const float4* v, __global float4* xs,
                             __global float4* vs, __global const float4* accel, __global float4* sum_x,
                             __global float4* sum_v, float weight, float c_h, int first) {
  const float4 zero = (float4)(0.0f);
  const ats_rk_stage_state s = ats_rk_stage(x[i], v[i], first ? v[i] : vs[i], accel[i], first ? zero : sum_x[i],
                                            first ? zero : sum_v[i], weight, c_h);
  sum_x[i] = s.sum_x;
  sum_v[i] = s.sum_v;
  xs[i] = s.xs;
  vs[i] = s.vs;
}

/* The last stage (common/particle_step.h). */
ATS_TASK void explicit_finish(int i, __global float4* x, __global float4* v, __global const float4* vs,
                              __global const float4* accel, __global const float4* sum_x, __global const float4* sum_v,
                              float weight, float h_sum) {
  const ats_particle_state s = ats_rk_finish(x[i], v[i], vs[i], accel[i], sum_x[i], sum_v[i], weight, h_sum);
  x[i] = s.x;
  v[i] = s.v;
}
