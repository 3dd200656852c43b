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

ATS_TASK void xpbd_predict(int i, __global float4* x, __global float4* v, __global float4* x_prev, float dt, float gx,
                           float gy, float gz, float damp) {
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
  const ats_distance_step s = gamma > 0.0f
                                  ? ats_xpbd_distance_damped(xyz(pa), pa.w, xyz(pb), pb.w, con.rest, con.compliance, l,
                                                             dt, xyz(x_start[con.a]), xyz(x_start[con.b]), gamma)
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
/* Distance constraints (common/xpbd_distance.h: ats_xpbd_distance and, where
 * the set has a damped spring, ats_xpbd_distance_damped: the same operations)
 * of one batch of 8 as float8 lanes: gather, solve, scatter. A batch's lanes
 * share no particle, so this equals the lanes one after another. inv_h = 0:
 * no spring of the set is damped and x_start is not read; otherwise an
 * undamped lane has gamma 0, for which the damped formula is the undamped
 * one ((1 + 0)(wa + wb) = wa + wb, less 0 · moved). pocl's compiler left the
 * scalar lane loop scalar (vsqrtss). */
static inline void xpbd_stretch_lanes8(int k0, __global float4* x, __global const ats_distance_c* c,
                                       __global float* lambda, float dt, int reset, __global const float4* x_start,
                                       float inv_h, int n) {
  float ax[8], ay[8], az[8], aw[8], bx[8], by[8], bz[8], bw[8], rest[8], comp[8], damp[8];
  int ia[8], ib[8];
  ATS_UNROLL for (int l = 0; l < 8; ++l) {
    const ats_distance_c con = c[k0 + l];
    const int live = con.a < n;
    ia[l] = live ? con.a : -1;
    ib[l] = con.b;
    const float4 pa = x[live ? con.a : 0];
    const float4 pb = x[live ? con.b : 0];
    ax[l] = pa.x;
    ay[l] = pa.y;
    az[l] = pa.z;
    aw[l] = pa.w;
    bx[l] = pb.x;
    by[l] = pb.y;
    bz[l] = pb.z;
    bw[l] = pb.w;
    rest[l] = con.rest;
    comp[l] = con.compliance;
    damp[l] = con.damping;
  }
  const float8 lam = reset ? (float8)(0.0f) : vload8(0, lambda + k0);
  const float8 wa = vload8(0, aw), wb = vload8(0, bw);
  const float8 dx = vload8(0, ax) - vload8(0, bx), dy = vload8(0, ay) - vload8(0, by),
               dz = vload8(0, az) - vload8(0, bz);
  const float8 alpha = vload8(0, comp) / (dt * dt);
  const float8 len = sqrt(dx * dx + dy * dy + dz * dz);
  float8 denom = wa + wb + alpha;
  const float8 inv_len = 1.0f / len;
  float8 moved = (float8)(0.0f), gamma = (float8)(0.0f);
  if (inv_h > 0.0f) {
    float mx[8], my[8], mz[8];
    ATS_UNROLL for (int l = 0; l < 8; ++l) {
      const float4 a0 = x_start[ia[l] >= 0 ? ia[l] : 0];
      const float4 b0 = x_start[ia[l] >= 0 ? ib[l] : 0];
      mx[l] = (ax[l] - a0.x) - (bx[l] - b0.x);
      my[l] = (ay[l] - a0.y) - (by[l] - b0.y);
      mz[l] = (az[l] - a0.z) - (bz[l] - b0.z);
    }
    gamma = vload8(0, damp) * inv_h;
    moved = dx * inv_len * vload8(0, mx) + dy * inv_len * vload8(0, my) + dz * inv_len * vload8(0, mz);
    denom = (1.0f + gamma) * (wa + wb) + alpha;
  }
  const int8 solved = len > 1e-20f && denom > 0.0f;
  const float8 dl = select((float8)(0.0f), (-(len - vload8(0, rest)) - alpha * lam - gamma * moved) / denom, solved);
  const float8 inv = select((float8)(0.0f), inv_len, solved);
  const float8 nx = dx * inv, ny = dy * inv, nz = dz * inv;
  vstore8(lam + dl, 0, lambda + k0);
  const float8 sa = wa * dl, sb = -wb * dl;
  float ox[8], oy[8], oz[8], qx[8], qy[8], qz[8];
  vstore8(vload8(0, ax) + nx * sa, 0, ox);
  vstore8(vload8(0, ay) + ny * sa, 0, oy);
  vstore8(vload8(0, az) + nz * sa, 0, oz);
  vstore8(vload8(0, bx) + nx * sb, 0, qx);
  vstore8(vload8(0, by) + ny * sb, 0, qy);
  vstore8(vload8(0, bz) + nz * sb, 0, qz);
  ATS_UNROLL for (int l = 0; l < 8; ++l) {
    if (ia[l] >= 0) {
      x[ia[l]] = (float4)(ox[l], oy[l], oz[l], aw[l]);
      x[ib[l]] = (float4)(qx[l], qy[l], qz[l], bw[l]);
    }
  }
}

ATS_TASK void xpbd_stretch_batches(int i, __global float4* x, __global const ats_distance_c* c, __global float* lambda,
                                   float dt, int reset, __global const float4* x_start, float inv_h, int batches,
                                   int n) {
  (void)i;
  for (int b = 0; b < batches; ++b) {
    const int k0 = b * ATS_XPBD_BATCH_WIDTH;
    if (ATS_XPBD_BATCH_WIDTH == 8) {
      xpbd_stretch_lanes8(k0, x, c, lambda, dt, reset, x_start, inv_h, n);
      continue;
    }
    ATS_UNROLL for (int l = 0; l < ATS_XPBD_BATCH_WIDTH; ++l) {
      if (c[k0 + l].a < n) xpbd_stretch(k0 + l, x, c, lambda, dt, reset, x_start, inv_h);
    }
  }
}

/* The four particles v (ids, -1 in a dummy lane, which reads particle 0) of
 * 8 elements as lanes, and back. */
static inline void xpbd_gather_particles8(__global const float4* x, int v[4][8], float px[4][8], float py[4][8],
                                          float pz[4][8], float pw[4][8]) {
  ATS_UNROLL for (int l = 0; l < 8; ++l) {
    ATS_UNROLL for (int j = 0; j < 4; ++j) {
      const float4 q = x[v[j][l] >= 0 ? v[j][l] : 0];
      px[j][l] = q.x;
      py[j][l] = q.y;
      pz[j][l] = q.z;
      pw[j][l] = q.w;
    }
  }
}
/* The four particles of each of the 8 stencils from element k0, as lanes. */
static inline void xpbd_gather_stencils8(int k0, __global const float4* x, __global const ats_bend_c* c, int n,
                                         int v[4][8], float px[4][8], float py[4][8], float pz[4][8], float pw[4][8]) {
  ATS_UNROLL for (int l = 0; l < 8; ++l) {
    const int live = c[k0 + l].v[0] < n;
    ATS_UNROLL for (int j = 0; j < 4; ++j) v[j][l] = live ? c[k0 + l].v[j] : -1;
  }
  xpbd_gather_particles8(x, v, px, py, pz, pw);
}
static inline void xpbd_scatter_stencils8(__global float4* x, int v[4][8], float px[4][8], float py[4][8],
                                          float pz[4][8], float pw[4][8]) {
  ATS_UNROLL for (int l = 0; l < 8; ++l) {
    if (v[0][l] >= 0) {
      ATS_UNROLL for (int j = 0; j < 4; ++j) x[v[j][l]] = (float4)(px[j][l], py[j][l], pz[j][l], pw[j][l]);
    }
  }
}

/* Isometric bending stencils (common/xpbd_bending.h, ats_xpbd_bend: the same
 * operations) of one batch of 8 as float8 lanes; a batch with a dihedral
 * stencil takes the scalar lanes instead. */
static inline void xpbd_bend_batch8(int k0, __global float4* x, __global const ats_bend_c* c, __global float4* lambda,
                                    float dt, int reset, int n) {
  float px[4][8], py[4][8], pz[4][8], pw[4][8], kk[4][8], sc[8], comp[8], lx[8], ly[8], lz[8];
  int v[4][8];
  xpbd_gather_stencils8(k0, x, c, n, v, px, py, pz, pw);
  ATS_UNROLL for (int l = 0; l < 8; ++l) {
    const ats_bend_c con = c[k0 + l];
    ATS_UNROLL for (int j = 0; j < 4; ++j) kk[j][l] = con.K[j];
    sc[l] = con.scale;
    comp[l] = con.compliance;
    const float4 l4 = reset ? (float4)(0.0f) : lambda[k0 + l];
    lx[l] = l4.x;
    ly[l] = l4.y;
    lz[l] = l4.z;
  }
  const float8 scale = vload8(0, sc);
  const float8 alpha = vload8(0, comp) / (dt * dt);
  float8 denom = alpha;
  float8 cx = (float8)(0.0f), cy = cx, cz = cx;
  ATS_UNROLL for (int j = 0; j < 4; ++j) {
    const float8 k = vload8(0, kk[j]);
    denom += scale * vload8(0, pw[j]) * k * k;
    cx += vload8(0, px[j]) * k;
    cy += vload8(0, py[j]) * k;
    cz += vload8(0, pz[j]) * k;
  }
  const float8 root = sqrt(scale);
  const float8 f = select((float8)(0.0f), -1.0f / denom, denom > 0.0f);
  const float8 dlx = (cx * root + vload8(0, lx) * alpha) * f;
  const float8 dly = (cy * root + vload8(0, ly) * alpha) * f;
  const float8 dlz = (cz * root + vload8(0, lz) * alpha) * f;
  float ox[8], oy[8], oz[8];
  vstore8(dlx, 0, ox);
  vstore8(dly, 0, oy);
  vstore8(dlz, 0, oz);
  ATS_UNROLL for (int l = 0; l < 8; ++l) lambda[k0 + l] = (float4)(lx[l] + ox[l], ly[l] + oy[l], lz[l] + oz[l], 0.0f);
  ATS_UNROLL for (int j = 0; j < 4; ++j) {
    const float8 g = vload8(0, pw[j]) * root * vload8(0, kk[j]);
    vstore8(vload8(0, px[j]) + dlx * g, 0, px[j]);
    vstore8(vload8(0, py[j]) + dly * g, 0, py[j]);
    vstore8(vload8(0, pz[j]) + dlz * g, 0, pz[j]);
  }
  xpbd_scatter_stencils8(x, v, px, py, pz, pw);
}

/* Dihedral stencils (common/xpbd_bending.h ats_xpbd_dihedral with the angle
 * and its gradient of common/energy_dihedral.h: the same operations) of one
 * batch of 8 as float8 lanes. A dummy lane (first particle n or past it)
 * computes on particle 0 and writes nothing. */
static inline void xpbd_dihedral_batch8(int k0, __global float4* x, __global const ats_bend_c* c,
                                        __global float4* lambda, float dt, int reset, int n) {
  float px[4][8], py[4][8], pz[4][8], pw[4][8], rest[8], sc[8], comp[8], lx[8], ly[8], lz[8];
  int v[4][8];
  xpbd_gather_stencils8(k0, x, c, n, v, px, py, pz, pw);
  ATS_UNROLL for (int l = 0; l < 8; ++l) {
    const ats_bend_c con = c[k0 + l];
    rest[l] = con.rest_angle;
    sc[l] = con.scale;
    comp[l] = con.compliance;
    const float4 l4 = reset ? (float4)(0.0f) : lambda[k0 + l];
    lx[l] = l4.x;
    ly[l] = l4.y;
    lz[l] = l4.z;
  }
  float8 X[4], Y[4], Z[4];
  ATS_UNROLL for (int j = 0; j < 4; ++j) {
    X[j] = vload8(0, px[j]);
    Y[j] = vload8(0, py[j]);
    Z[j] = vload8(0, pz[j]);
  }
  const float8 ex = X[1] - X[0], ey = Y[1] - Y[0], ez = Z[1] - Z[0];
  const float8 ax = X[2] - X[0], ay = Y[2] - Y[0], az = Z[2] - Z[0];
  const float8 bx = X[3] - X[0], by = Y[3] - Y[0], bz = Z[3] - Z[0];
  /* n_a = e x (x2 - x0), n_b = (x3 - x0) x e */
  const float8 nax = ey * az - ez * ay, nay = ez * ax - ex * az, naz = ex * ay - ey * ax;
  const float8 nbx = by * ez - bz * ey, nby = bz * ex - bx * ez, nbz = bx * ey - by * ex;
  const float8 le2 = ex * ex + ey * ey + ez * ez;
  const float8 na2 = nax * nax + nay * nay + naz * naz;
  const float8 nb2 = nbx * nbx + nby * nby + nbz * nbz;
  const int8 ok = le2 > 0.0f && na2 > 0.0f && nb2 > 0.0f;
  const float8 le = sqrt(le2);
  const float8 s2 = select((float8)(0.0f), le / na2, ok), s3 = select((float8)(0.0f), le / nb2, ok);
  const float8 t2 = select((float8)(0.0f), (ax * ex + ay * ey + az * ez) / le2, ok);
  const float8 t3 = select((float8)(0.0f), (bx * ex + by * ey + bz * ez) / le2, ok);
  float8 gx[4], gy[4], gz[4];
  gx[2] = nax * s2;
  gy[2] = nay * s2;
  gz[2] = naz * s2;
  gx[3] = nbx * s3;
  gy[3] = nby * s3;
  gz[3] = nbz * s3;
  gx[0] = gx[2] * (t2 - 1.0f) + gx[3] * (t3 - 1.0f);
  gy[0] = gy[2] * (t2 - 1.0f) + gy[3] * (t3 - 1.0f);
  gz[0] = gz[2] * (t2 - 1.0f) + gz[3] * (t3 - 1.0f);
  gx[1] = (gx[2] * t2 + gx[3] * t3) * -1.0f;
  gy[1] = (gy[2] * t2 + gy[3] * t3) * -1.0f;
  gz[1] = (gz[2] * t2 + gz[3] * t3) * -1.0f;
  const float8 alpha = vload8(0, comp) / (2.0f * vload8(0, sc) * dt * dt);
  float8 denom = alpha;
  ATS_UNROLL for (int j = 0; j < 4; ++j) denom += vload8(0, pw[j]) * (gx[j] * gx[j] + gy[j] * gy[j] + gz[j] * gz[j]);
  /* theta = atan2(e/|e| . (n_b x n_a), n_a . n_b), 0 for a zero edge */
  const float8 cx = nby * naz - nbz * nay, cy = nbz * nax - nbx * naz, cz = nbx * nay - nby * nax;
  const float8 theta =
      select((float8)(0.0f), atan2((cx * ex + cy * ey + cz * ez) / le, nax * nbx + nay * nby + naz * nbz), le > 0.0f);
  const float8 cval = theta - vload8(0, rest);
  const float8 dl = select((float8)(0.0f), -(cval + alpha * vload8(0, lx)) / denom, denom > 0.0f);
  float o[8];
  vstore8(dl, 0, o);
  ATS_UNROLL for (int l = 0; l < 8; ++l) lambda[k0 + l] = (float4)(lx[l] + o[l], ly[l] + 0.0f, lz[l] + 0.0f, 0.0f);
  ATS_UNROLL for (int j = 0; j < 4; ++j) {
    const float8 f = vload8(0, pw[j]) * dl;
    vstore8(X[j] + gx[j] * f, 0, px[j]);
    vstore8(Y[j] + gy[j] * f, 0, py[j]);
    vstore8(Z[j] + gz[j] * f, 0, pz[j]);
  }
  xpbd_scatter_stencils8(x, v, px, py, pz, pw);
}

/* One batch of bending stencils from element k0: float8 lanes when its live
 * stencils are all isometric or all dihedral, else the lanes one after
 * another. */
static inline void xpbd_bend_batch(int k0, __global float4* x, __global const ats_bend_c* c, __global float4* lambda,
                                   float dt, int reset, int n) {
  int dihedral = 0, isometric = 0;
  for (int l = 0; l < ATS_XPBD_BATCH_WIDTH; ++l) {
    if (c[k0 + l].v[0] >= n) continue;
    dihedral |= c[k0 + l].model == ATS_BEND_DIHEDRAL;
    isometric |= c[k0 + l].model != ATS_BEND_DIHEDRAL;
  }
  if (!dihedral && ATS_XPBD_BATCH_WIDTH == 8) {
    xpbd_bend_batch8(k0, x, c, lambda, dt, reset, n);
    return;
  }
  if (!isometric && ATS_XPBD_BATCH_WIDTH == 8) {
    xpbd_dihedral_batch8(k0, x, c, lambda, dt, reset, n);
    return;
  }
  for (int l = 0; l < ATS_XPBD_BATCH_WIDTH; ++l) {
    if (c[k0 + l].v[0] < n) xpbd_bend(k0 + l, x, c, lambda, dt, reset);
  }
}

ATS_TASK void xpbd_bend_batches(int i, __global float4* x, __global const ats_bend_c* c, __global float4* lambda,
                                float dt, int reset, int batches, int n) {
  (void)i;
  for (int b = 0; b < batches; ++b) xpbd_bend_batch(b * ATS_XPBD_BATCH_WIDTH, x, c, lambda, dt, reset, n);
}

/* solver.ordering: color_batches. Work-item i is batch i of a color block
 * cut into batches (solver/xpbd/xpbd_batches: color_batches): its lanes share
 * no particle with any other batch of the block, so a block's batches run in
 * any order and on any device, as a color block's elements do. */
ATS_TASK void xpbd_stretch_lanes(int i, __global float4* x, __global const ats_distance_c* c, __global float* lambda,
                                 float dt, int reset, __global const float4* x_start, float inv_h, int n) {
  const int k0 = i * ATS_XPBD_BATCH_WIDTH;
  if (ATS_XPBD_BATCH_WIDTH == 8) {
    xpbd_stretch_lanes8(k0, x, c, lambda, dt, reset, x_start, inv_h, n);
    return;
  }
  for (int l = 0; l < ATS_XPBD_BATCH_WIDTH; ++l) {
    if (c[k0 + l].a < n) xpbd_stretch(k0 + l, x, c, lambda, dt, reset, x_start, inv_h);
  }
}

ATS_TASK void xpbd_bend_lanes(int i, __global float4* x, __global const ats_bend_c* c, __global float4* lambda,
                              float dt, int reset, int n) {
  xpbd_bend_batch(i * ATS_XPBD_BATCH_WIDTH, x, c, lambda, dt, reset, n);
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
  ATS_UNROLL for (int r = 0; r < 3; ++r) dm_inv.r[r] =
      ats_v3(t.dm_inv[3 * r], t.dm_inv[3 * r + 1], t.dm_inv[3 * r + 2]);
  float lam[ATS_TET_LAMBDA_STRIDE];
  ATS_UNROLL for (int j = 0; j < ATS_TET_LAMBDA_STRIDE; ++j) lam[j] =
      reset ? 0.0f : lambda[ATS_TET_LAMBDA_STRIDE * i + j];
  ats_xpbd_tet(p, w, dm_inv, t.volume, t.mu, t.lambda, lam, dt);
  ATS_UNROLL for (int j = 0; j < ATS_TET_LAMBDA_STRIDE; ++j) lambda[ATS_TET_LAMBDA_STRIDE * i + j] = lam[j];
  ATS_UNROLL for (int j = 0; j < 4; ++j) x[t.v[j]] = (float4)(p[j].x, p[j].y, p[j].z, q[j].w);
}

/* StVK tets (common/xpbd_tet.h, ats_xpbd_tet: the same operations, the
 * seven strain constraints one after another) of one batch of 8 as float8
 * lanes. A dummy lane (first particle n or past it) computes on particle 0
 * and writes nothing; a constraint with k_c = 0 moves nothing in its lane. */
static inline void xpbd_tet_lanes8(int k0, __global float4* x, __global const ats_tet_c* c, __global float* lambda,
                                   float dt, int reset, int n) {
  float px[4][8], py[4][8], pz[4][8], pw[4][8], dm[9][8], vol[8], mu[8], la[8], lam[ATS_TET_LAMBDA_STRIDE][8];
  int v[4][8];
  ATS_UNROLL for (int l = 0; l < 8; ++l) {
    const ats_tet_c t = c[k0 + l];
    const int live = t.v[0] < n;
    ATS_UNROLL for (int j = 0; j < 4; ++j) v[j][l] = live ? t.v[j] : -1;
    ATS_UNROLL for (int r = 0; r < 9; ++r) dm[r][l] = t.dm_inv[r];
    vol[l] = t.volume;
    mu[l] = t.mu;
    la[l] = t.lambda;
    ATS_UNROLL for (int j = 0; j < ATS_TET_LAMBDA_STRIDE; ++j) lam[j][l] =
        reset ? 0.0f : lambda[ATS_TET_LAMBDA_STRIDE * (k0 + l) + j];
  }
  xpbd_gather_particles8(x, v, px, py, pz, pw);
  float8 P[4][3], W[4], D[3][3], B[4][3];
  ATS_UNROLL for (int a = 0; a < 4; ++a) {
    P[a][0] = vload8(0, px[a]);
    P[a][1] = vload8(0, py[a]);
    P[a][2] = vload8(0, pz[a]);
    W[a] = vload8(0, pw[a]);
  }
  /* shape vectors: b_a = row a-1 of Dm^-1 (a = 1, 2, 3), b_0 = -(b_1 + b_2 + b_3) */
  ATS_UNROLL for (int r = 0; r < 3; ++r) {
    ATS_UNROLL for (int s = 0; s < 3; ++s) {
      D[r][s] = vload8(0, dm[3 * r + s]);
      B[r + 1][s] = D[r][s];
    }
  }
  ATS_UNROLL for (int s = 0; s < 3; ++s) B[0][s] = ((D[0][s] + D[1][s]) + D[2][s]) * -1.0f;
  const float8 volume = vload8(0, vol), mu8 = vload8(0, mu);
  ATS_UNROLL for (int cc = 0; cc < ATS_TET_STRAIN_CONSTRAINTS; ++cc) {
    const float8 k = cc < 3 ? 2.0f * mu8 * volume : (cc < 6 ? 4.0f * mu8 * volume : vload8(0, la) * volume);
    const int8 active = k > 0.0f;
    const float8 alpha = 1.0f / (k * dt * dt);
    /* F = sum_{a=1..3} (x_a - x_0) b_a^T, then G = F - I */
    float8 F[3][3], G[3][3];
    ATS_UNROLL for (int i = 0; i < 3; ++i) {
      const float8 e0 = P[1][i] - P[0][i], e1 = P[2][i] - P[0][i], e2 = P[3][i] - P[0][i];
      ATS_UNROLL for (int j = 0; j < 3; ++j) {
        F[i][j] = D[0][j] * e0 + D[1][j] * e1 + D[2][j] * e2;
        G[i][j] = F[i][j] - (i == j ? 1.0f : 0.0f);
      }
    }
    /* E_ij = 1/2 (G_ij + G_ji + sum_k G_ki G_kj) */
    const int ci = ats_tet_strain_i(cc < 6 ? cc : 0), cj = ats_tet_strain_j(cc < 6 ? cc : 0);
    float8 value;
    if (cc == 6) {
      value = (float8)(0.0f);
      ATS_UNROLL for (int d = 0; d < 3; ++d) value +=
          ((G[d][d] + G[d][d]) + (G[0][d] * G[0][d] + G[1][d] * G[1][d] + G[2][d] * G[2][d])) * 0.5f;
    } else {
      value = ((G[ci][cj] + G[cj][ci]) + (G[0][ci] * G[0][cj] + G[1][ci] * G[1][cj] + G[2][ci] * G[2][cj])) * 0.5f;
    }
    /* grad_a C: 1/2 (b_a[j] f_i + b_a[i] f_j) with f_i column i of F; tr E: F b_a */
    float8 g[4][3];
    float8 denom = alpha;
    ATS_UNROLL for (int a = 0; a < 4; ++a) {
      ATS_UNROLL for (int r = 0; r < 3; ++r) {
        g[a][r] = cc == 6 ? F[r][0] * B[a][0] + F[r][1] * B[a][1] + F[r][2] * B[a][2]
                          : (F[r][ci] * B[a][cj] + F[r][cj] * B[a][ci]) * 0.5f;
      }
      denom += W[a] * (g[a][0] * g[a][0] + g[a][1] * g[a][1] + g[a][2] * g[a][2]);
    }
    const float8 l0 = vload8(0, lam[cc]);
    const float8 dl = select((float8)(0.0f), (-value - alpha * l0) / denom, active);
    vstore8(l0 + dl, 0, lam[cc]);
    ATS_UNROLL for (int a = 0; a < 4; ++a) {
      const float8 f = W[a] * dl;
      ATS_UNROLL for (int r = 0; r < 3; ++r) P[a][r] += g[a][r] * f;
    }
  }
  ATS_UNROLL for (int a = 0; a < 4; ++a) {
    vstore8(P[a][0], 0, px[a]);
    vstore8(P[a][1], 0, py[a]);
    vstore8(P[a][2], 0, pz[a]);
  }
  ATS_UNROLL for (int l = 0; l < 8; ++l) {
    if (v[0][l] >= 0) {
      ATS_UNROLL for (int j = 0; j < ATS_TET_LAMBDA_STRIDE; ++j) lambda[ATS_TET_LAMBDA_STRIDE * (k0 + l) + j] =
          lam[j][l];
    }
  }
  xpbd_scatter_stencils8(x, v, px, py, pz, pw);
}

/* One batch of tets from element k0: float8 lanes, or the lanes one after
 * another for another batch width. */
static inline void xpbd_tet_batch(int k0, __global float4* x, __global const ats_tet_c* c, __global float* lambda,
                                  float dt, int reset, int n) {
  if (ATS_XPBD_BATCH_WIDTH == 8) {
    xpbd_tet_lanes8(k0, x, c, lambda, dt, reset, n);
    return;
  }
  for (int l = 0; l < ATS_XPBD_BATCH_WIDTH; ++l) {
    if (c[k0 + l].v[0] < n) xpbd_tet(k0 + l, x, c, lambda, dt, reset);
  }
}

/* solver.ordering: color_batches (work-item i = batch i of a tet color block)
 * and batches (one work-item sweeps the padded set), as for the cloth sets. */
ATS_TASK void xpbd_tet_lanes(int i, __global float4* x, __global const ats_tet_c* c, __global float* lambda, float dt,
                             int reset, int n) {
  xpbd_tet_batch(i * ATS_XPBD_BATCH_WIDTH, x, c, lambda, dt, reset, n);
}

ATS_TASK void xpbd_tet_batches(int i, __global float4* x, __global const ats_tet_c* c, __global float* lambda, float dt,
                               int reset, int batches, int n) {
  (void)i;
  for (int b = 0; b < batches; ++b) xpbd_tet_batch(b * ATS_XPBD_BATCH_WIDTH, x, c, lambda, dt, reset, n);
}
