#pragma once
// One group of 8 XPBD elements that share no particle as 8 float lanes, for
// the bench_native loops over batches (bench/plain_xpbd_batches.hpp,
// bench/plain_xpbd_color_batches.hpp): the operations of kernels/xpbd/
// xpbd.cl's xpbd_stretch_batch8, xpbd_bend_batch8 and xpbd_tet_lanes8, one 8-float vector
// (GCC vector extensions; one AVX register under -march=native). A group
// with a damped spring or a dihedral stencil runs its lanes one after
// another with the scalar math, as the kernels do. A lane whose first
// particle is n or past it is a padding dummy and does nothing.
#include <cmath>

#include "common/xpbd_bending.h"
#include "common/xpbd_distance.h"
#include "common/xpbd_tet.h"
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

// StVK tets con[0..8) with their multipliers lambda[0..8 * ATS_TET_LAMBDA_STRIDE)
// (common/xpbd_tet.h's seven strain constraints one after another).
inline void tet_group8(solver::Float4* x, const ats_tet_c* con, float* lambda, int n, float dt, bool reset) {
  constexpr int kStride = ATS_TET_LAMBDA_STRIDE;
  alignas(32) float px[4][8], py[4][8], pz[4][8], pw[4][8], dm[9][8], vol[8], mu[8], la[8], lam[kStride][8];
  int v[4][8];
  for (int l = 0; l < 8; ++l) {
    const ats_tet_c& t = con[l];
    const bool live = t.v[0] < n;
    for (int j = 0; j < 4; ++j) {
      v[j][l] = live ? t.v[j] : -1;
      const solver::Float4 q = x[live ? t.v[j] : 0];
      px[j][l] = q.x, py[j][l] = q.y, pz[j][l] = q.z, pw[j][l] = q.w;
    }
    for (int r = 0; r < 9; ++r) dm[r][l] = t.dm_inv[r];
    vol[l] = t.volume, mu[l] = t.mu, la[l] = t.lambda;
    for (int c = 0; c < kStride; ++c) lam[c][l] = reset ? 0.0f : lambda[kStride * l + c];
  }
  F8 P[4][3], W[4], D[3][3], B[4][3];
  for (int a = 0; a < 4; ++a) P[a][0] = load(px[a]), P[a][1] = load(py[a]), P[a][2] = load(pz[a]), W[a] = load(pw[a]);
  for (int r = 0; r < 3; ++r) {
    for (int s = 0; s < 3; ++s) D[r][s] = B[r + 1][s] = load(dm[3 * r + s]);
  }
  for (int s = 0; s < 3; ++s) B[0][s] = ((D[0][s] + D[1][s]) + D[2][s]) * -1.0f;
  const F8 volume = load(vol), mu8 = load(mu), zero = splat(0.0f);
  for (int c = 0; c < ATS_TET_STRAIN_CONSTRAINTS; ++c) {
    const F8 k = c < 3 ? 2.0f * mu8 * volume : (c < 6 ? 4.0f * mu8 * volume : load(la) * volume);
    const F8 alpha = 1.0f / (k * dt * dt);
    F8 F[3][3], G[3][3];
    for (int i = 0; i < 3; ++i) {
      const F8 e0 = P[1][i] - P[0][i], e1 = P[2][i] - P[0][i], e2 = P[3][i] - P[0][i];
      for (int j = 0; j < 3; ++j) {
        F[i][j] = D[0][j] * e0 + D[1][j] * e1 + D[2][j] * e2;
        G[i][j] = F[i][j] - (i == j ? 1.0f : 0.0f);
      }
    }
    const int ci = ats_tet_strain_i(c < 6 ? c : 0), cj = ats_tet_strain_j(c < 6 ? c : 0);
    F8 value = zero;
    if (c == 6) {
      for (int d = 0; d < 3; ++d)
        value += ((G[d][d] + G[d][d]) + (G[0][d] * G[0][d] + G[1][d] * G[1][d] + G[2][d] * G[2][d])) * 0.5f;
    } else {
      value = ((G[ci][cj] + G[cj][ci]) + (G[0][ci] * G[0][cj] + G[1][ci] * G[1][cj] + G[2][ci] * G[2][cj])) * 0.5f;
    }
    F8 g[4][3], denom = alpha;
    for (int a = 0; a < 4; ++a) {
      for (int r = 0; r < 3; ++r) {
        g[a][r] = c == 6 ? F[r][0] * B[a][0] + F[r][1] * B[a][1] + F[r][2] * B[a][2]
                         : (F[r][ci] * B[a][cj] + F[r][cj] * B[a][ci]) * 0.5f;
      }
      denom += W[a] * (g[a][0] * g[a][0] + g[a][1] * g[a][1] + g[a][2] * g[a][2]);
    }
    const F8 l0 = load(lam[c]);
    const F8 dl = select(k > 0.0f, (-value - alpha * l0) / denom, zero);
    const F8 l1 = l0 + dl;
    __builtin_memcpy(lam[c], &l1, sizeof l1);
    for (int a = 0; a < 4; ++a) {
      const F8 f = W[a] * dl;
      for (int r = 0; r < 3; ++r) P[a][r] += g[a][r] * f;
    }
  }
  for (int l = 0; l < 8; ++l) {
    if (v[0][l] < 0) continue;
    for (int c = 0; c < kStride; ++c) lambda[kStride * l + c] = lam[c][l];
    for (int j = 0; j < 4; ++j) {
      if (pw[j][l] != 0.0f) x[v[j][l]] = {P[j][0][l], P[j][1][l], P[j][2][l], pw[j][l]};
    }
  }
}

}  // namespace atssim::bench::lanes
