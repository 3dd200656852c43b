#pragma once
// One group of 8 XPBD elements that share no particle as 8 float lanes, for
// the bench_native loops over batches (bench/plain_xpbd_batches.hpp,
// bench/plain_xpbd_color_batches.hpp): the operations of kernels/xpbd/
// xpbd.cl's xpbd_stretch_batch8 and xpbd_bend_batch8, one 8-float vector
// (GCC vector extensions; one AVX register under -march=native). A group
// with a damped spring or a dihedral stencil runs its lanes one after
// another with the scalar math, as the kernels do. A lane whose first
// particle is n or past it is a padding dummy and does nothing.
#include <cmath>

#include "common/xpbd_bending.h"
#include "common/xpbd_distance.h"
#include "solver/layout/sim_layout.hpp"

namespace atssim::bench::lanes {

typedef float F8 __attribute__((vector_size(32)));
typedef int I8 __attribute__((vector_size(32)));

inline F8 load(const float* p) {
  F8 v;
  __builtin_memcpy(&v, p, sizeof v);
  return v;
}
inline F8 splat(float s) { return F8{s, s, s, s, s, s, s, s}; }
inline F8 sqrt8(F8 v) {
  for (int l = 0; l < 8; ++l) v[l] = std::sqrt(v[l]);  // vsqrtps under -march=native
  return v;
}
inline F8 select(I8 m, F8 a, F8 b) { return m ? a : b; }  // a where m, else b
inline ats_vec3 xyz(const solver::Float4& p) { return ats_v3(p.x, p.y, p.z); }
inline void add(solver::Float4& p, ats_vec3 d) {
  if (p.w == 0.0f) return;
  p.x += d.x;
  p.y += d.y;
  p.z += d.z;
}

// Distance constraints con[0..8) with their multipliers lambda[0..8);
// inv_h != 0: damped springs, the lanes in turn (x0: the substep's start).
// A pinned particle (w = 0) is not stored: a color block may share one, and
// its lanes leave it as it was.
inline void stretch_group8(solver::Float4* x, const solver::Float4* x0, const ats_distance_c* con, float* lambda, int n,
                           float dt, float inv_h, bool reset) {
  if (inv_h != 0.0f) {  // damped springs: the lanes in turn (xpbd_stretch_batches' scalar path)
    for (int l = 0; l < 8; ++l) {
      const ats_distance_c& c = con[l];
      if (c.a >= n) continue;
      solver::Float4& pa = x[c.a];
      solver::Float4& pb = x[c.b];
      const float lam = reset ? 0.0f : lambda[l];
      const ats_distance_step s = ats_xpbd_distance_damped(xyz(pa), pa.w, xyz(pb), pb.w, c.rest, c.compliance, lam, dt,
                                                           xyz(x0[c.a]), xyz(x0[c.b]), c.damping * inv_h);
      lambda[l] = lam + s.dlambda;
      add(pa, s.dxa);
      add(pb, s.dxb);
    }
    return;
  }
  alignas(32) float ax[8], ay[8], az[8], aw[8], bx[8], by[8], bz[8], bw[8], rest[8], comp[8];
  int ia[8], ib[8];
  for (int l = 0; l < 8; ++l) {
    const ats_distance_c c = con[l];
    const bool live = c.a < n;
    ia[l] = live ? c.a : -1;
    ib[l] = c.b;
    const solver::Float4 pa = x[live ? c.a : 0];
    const solver::Float4 pb = x[live ? c.b : 0];
    ax[l] = pa.x, ay[l] = pa.y, az[l] = pa.z, aw[l] = pa.w;
    bx[l] = pb.x, by[l] = pb.y, bz[l] = pb.z, bw[l] = pb.w;
    rest[l] = c.rest;
    comp[l] = c.compliance;
  }
  const F8 zero = splat(0.0f);
  const F8 lam = reset ? zero : load(lambda);
  const F8 wa = load(aw), wb = load(bw);
  const F8 dx = load(ax) - load(bx), dy = load(ay) - load(by), dz = load(az) - load(bz);
  const F8 alpha = load(comp) / (dt * dt);
  const F8 len = sqrt8(dx * dx + dy * dy + dz * dz);
  const F8 denom = wa + wb + alpha;
  const I8 solved = (len > 1e-20f) & (denom > 0.0f);
  const F8 dl = select(solved, (-(len - load(rest)) - alpha * lam) / denom, zero);
  const F8 inv = select(solved, 1.0f / len, zero);
  const F8 nx = dx * inv, ny = dy * inv, nz = dz * inv;
  const F8 out = lam + dl;
  __builtin_memcpy(lambda, &out, sizeof out);
  const F8 sa = wa * dl, sb = -wb * dl;
  const F8 ox = load(ax) + nx * sa, oy = load(ay) + ny * sa, oz = load(az) + nz * sa;
  const F8 qx = load(bx) + nx * sb, qy = load(by) + ny * sb, qz = load(bz) + nz * sb;
  for (int l = 0; l < 8; ++l) {
    if (ia[l] < 0) continue;
    if (aw[l] != 0.0f) x[ia[l]] = {ox[l], oy[l], oz[l], aw[l]};
    if (bw[l] != 0.0f) x[ib[l]] = {qx[l], qy[l], qz[l], bw[l]};
  }
}

// Bending stencils con[0..8) with their multipliers lambda[0..24) (3 each).
inline void bend_group8(solver::Float4* x, const ats_bend_c* con, float* lambda, int n, float dt, bool reset) {
  bool dihedral = false;
  for (int l = 0; l < 8; ++l) dihedral |= con[l].model == ATS_BEND_DIHEDRAL;
  if (dihedral) {  // the lanes in turn (xpbd_bend_batches' scalar path)
    for (int l = 0; l < 8; ++l) {
      const ats_bend_c& c = con[l];
      if (c.v[0] >= n) continue;
      ats_vec3 p[4];
      float w[4];
      for (int j = 0; j < 4; ++j) p[j] = xyz(x[c.v[j]]), w[j] = x[c.v[j]].w;
      float* lam = lambda + 3 * l;
      const ats_vec3 lv = reset ? ats_v3(0, 0, 0) : ats_v3(lam[0], lam[1], lam[2]);
      const ats_bend_step s = ats_xpbd_bend_element(p, w, &c, lv, dt);
      lam[0] = lv.x + s.dlambda.x, lam[1] = lv.y + s.dlambda.y, lam[2] = lv.z + s.dlambda.z;
      for (int j = 0; j < 4; ++j) add(x[c.v[j]], s.dx[j]);
    }
    return;
  }
  alignas(32) float px[4][8], py[4][8], pz[4][8], pw[4][8], kk[4][8], sc[8], comp[8], lx[8], ly[8], lz[8];
  int v[4][8];
  for (int l = 0; l < 8; ++l) {
    const ats_bend_c& c = con[l];
    const bool live = c.v[0] < n;
    for (int j = 0; j < 4; ++j) {
      v[j][l] = live ? c.v[j] : -1;
      const solver::Float4 q = x[live ? c.v[j] : 0];
      px[j][l] = q.x, py[j][l] = q.y, pz[j][l] = q.z, pw[j][l] = q.w;
      kk[j][l] = c.K[j];
    }
    sc[l] = c.scale;
    comp[l] = c.compliance;
    lx[l] = reset ? 0.0f : lambda[3 * l];
    ly[l] = reset ? 0.0f : lambda[3 * l + 1];
    lz[l] = reset ? 0.0f : lambda[3 * l + 2];
  }
  const F8 zero = splat(0.0f);
  const F8 scale = load(sc);
  const F8 alpha = load(comp) / (dt * dt);
  F8 denom = alpha, cx = zero, cy = zero, cz = zero;
  for (int j = 0; j < 4; ++j) {
    const F8 k = load(kk[j]);
    denom += scale * load(pw[j]) * k * k;
    cx += load(px[j]) * k;
    cy += load(py[j]) * k;
    cz += load(pz[j]) * k;
  }
  const F8 root = sqrt8(scale);
  const F8 f = select(denom > 0.0f, -1.0f / denom, zero);
  const F8 dlx = (cx * root + load(lx) * alpha) * f;
  const F8 dly = (cy * root + load(ly) * alpha) * f;
  const F8 dlz = (cz * root + load(lz) * alpha) * f;
  for (int l = 0; l < 8; ++l) {
    lambda[3 * l] = lx[l] + dlx[l];
    lambda[3 * l + 1] = ly[l] + dly[l];
    lambda[3 * l + 2] = lz[l] + dlz[l];
  }
  F8 ox[4], oy[4], oz[4];
  for (int j = 0; j < 4; ++j) {
    const F8 g = load(pw[j]) * root * load(kk[j]);
    ox[j] = load(px[j]) + dlx * g;
    oy[j] = load(py[j]) + dly * g;
    oz[j] = load(pz[j]) + dlz * g;
  }
  for (int l = 0; l < 8; ++l) {
    if (v[0][l] < 0) continue;
    for (int j = 0; j < 4; ++j) {
      if (pw[j][l] != 0.0f) x[v[j][l]] = {ox[j][l], oy[j][l], oz[j][l], pw[j][l]};
    }
  }
}

}  // namespace atssim::bench::lanes
