/* XPBD substep kernels (Macklin et al. 2016, small steps: lambdas restart
 * every substep). Positions are float4 with w = inverse mass (0 = pinned).
 * Each constraint kernel works on one color block, elements
 * [first, first + count) of its array, that share no movable particle. */
#include "common/ats_math.h"
#include "common/element_types.h"
#include "common/xpbd_distance.h"
#include "common/xpbd_bending.h"
#include "common/xpbd_tet.h"
#include "common/xpbd_batches.h"
#include "common/particle_steps.cl"
#include "common/contact_steps.cl"
#include "contact/self_contact.cl"
#include "async/merge.cl"

static inline ats_vec3 xyz(float4 p) { return ats_v3(p.x, p.y, p.z); }
static inline float4 add_xyz(float4 p, ats_vec3 d) { return (float4)(p.x + d.x, p.y + d.y, p.z + d.z, p.w); }

ATS_TASK void xpbd_predict(int i, __global float4* x, __global float4* v, __global float4* x_prev, float dt, float gx, float gy, float gz, float damp) {
  predict_particle(i, x, v, x_prev, dt, gx, gy, gz, damp);
}

/* inv_h = 1/h of the substep when some spring is damped (gamma = damping/h,
 * common/xpbd_distance.h), else 0; x_start = the substep's start. */
ATS_TASK void xpbd_stretch(int i, __global float4* x, __global const ats_distance_c* c, __global float* lambda,
                           float dt, int reset, __global const float4* x_start, float inv_h) {
  const ats_distance_c con = c[i];
  const float l = reset ? 0.0f : lambda[i];
  const float4 pa = x[con.a];
  const float4 pb = x[con.b];
  const float gamma = con.damping * inv_h;
  const ats_distance_step s =
      gamma > 0.0f ? ats_xpbd_distance_damped(xyz(pa), pa.w, xyz(pb), pb.w, con.rest, con.compliance, l, dt,
                                              xyz(x_start[con.a]), xyz(x_start[con.b]), gamma)
                   : ats_xpbd_distance(xyz(pa), pa.w, xyz(pb), pb.w, con.rest, con.compliance, l, dt);
  lambda[i] = l + s.dlambda;
  x[con.a] = add_xyz(pa, s.dxa);
  x[con.b] = add_xyz(pb, s.dxb);
}

ATS_TASK void xpbd_bend(int i, __global float4* x, __global const ats_bend_c* c, __global float4* lambda, float dt,
                        int reset) {
  const ats_bend_c con = c[i];
  ats_vec3 p[4];
  float w[4];
  float4 q[4];
  ATS_UNROLL for (int j = 0; j < 4; ++j) {
    q[j] = x[con.v[j]];
    p[j] = xyz(q[j]);
    w[j] = q[j].w;
  }
  const float4 l4 = reset ? (float4)(0.0f) : lambda[i];
  const ats_bend_step s = ats_xpbd_bend_element(p, w, &con, xyz(l4), dt);
  lambda[i] = (float4)(l4.x + s.dlambda.x, l4.y + s.dlambda.y, l4.z + s.dlambda.z, 0.0f);
  ATS_UNROLL for (int j = 0; j < 4; ++j) x[con.v[j]] = add_xyz(q[j], s.dx[j]);
}

/* solver.ordering: batches. One work-item sweeps a whole element set, padded
 * to batches of ATS_XPBD_BATCH_WIDTH elements that share no particle
 * (graph/simd_batches), batch after batch: a Gauss-Seidel order with no
 * barrier between colors. A lane whose first particle is n or past it is
 * NvCloth's padding dummy and does nothing. */
ATS_TASK void xpbd_stretch_batches(int i, __global float4* x, __global const ats_distance_c* c, __global float* lambda,
                                   float dt, int reset, __global const float4* x_start, float inv_h, int batches, int n) {
  (void)i;
  for (int b = 0; b < batches; ++b) {
    ATS_UNROLL for (int l = 0; l < ATS_XPBD_BATCH_WIDTH; ++l) {
      const int k = b * ATS_XPBD_BATCH_WIDTH + l;
      if (c[k].a < n) xpbd_stretch(k, x, c, lambda, dt, reset, x_start, inv_h);
    }
  }
}

ATS_TASK void xpbd_bend_batches(int i, __global float4* x, __global const ats_bend_c* c, __global float4* lambda,
                                float dt, int reset, int batches, int n) {
  (void)i;
  for (int b = 0; b < batches; ++b) {
    for (int l = 0; l < ATS_XPBD_BATCH_WIDTH; ++l) {
      const int k = b * ATS_XPBD_BATCH_WIDTH + l;
      if (c[k].v[0] < n) xpbd_bend(k, x, c, lambda, dt, reset);
    }
  }
}

/* One StVK tet per work-item: its seven strain constraints in sequence
 * (common/xpbd_tet.h); lambda holds ATS_TET_LAMBDA_STRIDE floats per tet. */
ATS_TASK void xpbd_tet(int i, __global float4* x, __global const ats_tet_c* c, __global float* lambda, float dt,
                       int reset) {
  const ats_tet_c t = c[i];
  ats_vec3 p[4];
  float w[4];
  float4 q[4];
  ATS_UNROLL for (int j = 0; j < 4; ++j) {
    q[j] = x[t.v[j]];
    p[j] = xyz(q[j]);
    w[j] = q[j].w;
  }
  ats_mat3 dm_inv;
  ATS_UNROLL for (int r = 0; r < 3; ++r) dm_inv.r[r] = ats_v3(t.dm_inv[3 * r], t.dm_inv[3 * r + 1], t.dm_inv[3 * r + 2]);
  float lam[ATS_TET_LAMBDA_STRIDE];
  ATS_UNROLL for (int j = 0; j < ATS_TET_LAMBDA_STRIDE; ++j) lam[j] = reset ? 0.0f : lambda[ATS_TET_LAMBDA_STRIDE * i + j];
  ats_xpbd_tet(p, w, dm_inv, t.volume, t.mu, t.lambda, lam, dt);
  ATS_UNROLL for (int j = 0; j < ATS_TET_LAMBDA_STRIDE; ++j) lambda[ATS_TET_LAMBDA_STRIDE * i + j] = lam[j];
  ATS_UNROLL for (int j = 0; j < 4; ++j) x[t.v[j]] = (float4)(p[j].x, p[j].y, p[j].z, q[j].w);
}
