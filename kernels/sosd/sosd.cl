/* Second-order Stencil Descent (Lan et al. 2023) in the hybrid Jacobi /
 * Gauss-Seidel form of the ATS paper (§5, "SOSD"): a stencil is one element
 * (a stretch edge, a bending stencil, a tetrahedron) and its vertices. Per
 * iteration:
 *   1. sosd_vertex_systems: every vertex's force f_a and Hessian block H_aa of
 *      the incremental potential (all incident elements), from x^k;
 *   2. sosd_<kind>: every stencil solves its local Newton system
 *      [H_aa  H_ab^e; H_ba^e  H_bb] d = f over its own vertices, the others
 *      fixed (diagonal blocks: the full vertex blocks; off-diagonal blocks:
 *      this element's coupling), and stores d per (element, slot);
 *   3. sosd_combine: a vertex that belongs to a stencil of the iteration's
 *      main Gauss-Seidel block takes that stencil's displacement (no two
 *      stencils of a block share a vertex); every other vertex takes the
 *      mean of its stencils' displacements (the Jacobi blocks); both scaled
 *      by a step length (solver.stencil_step, below 1: see sosd_plan.hpp).
 * Every step reads only what the step before wrote, so any cut of a step
 * between devices computes the same result. */
#pragma OPENCL FP_CONTRACT OFF /* the stretch energy's error-free transforms */

#include "common/ats_math.h"
#include "common/vertex_solve.h"
#include "common/vertex_system.cl"
#include "contact/self_contact.cl"
#include "contact/self_contact_terms.h"
#include "common/vertex_contact.h"
#include "common/contact_steps.cl"
#include "common/vertex_friction.cl"
#include "common/particle_steps.cl"
#include "async/merge.cl"

#define SOSD_MAX 12 /* 4 vertices x 3 */

/* sys[4 i] = (f, 0), sys[4 i + 1 .. 4 i + 3] = rows of H_ii. */
ATS_TASK void sosd_vertex_systems(int i, __global const float4* x, __global const float4* x_tilde,
                                  __global const int* adj_offsets, __global const int* adj,
                                  __global const ats_distance_c* stretch, __global const ats_bend_c* bend,
                                  __global const ats_tet_c* tets, __global float4* sys, float inv_h2,
                                  __global const ats_collider_c* colliders, int collider_count,
                                  __global const ats_mesh_near* near, __global const float4* x_start, float inv_h,
                                  __global const int4* sc_tris, __global const int2* sc_edges,
                                  __global const int* sc_inc, __global const int* sc_vt, __global const int* sc_tv,
                                  __global const int* sc_ee, __global const float* sc_bound, int sc_n, float sc_k,
                                  float sc_r, int sc_on) {
  if (x[i].w == 0.0f) return; /* pinned: never read */
  const vertex_system s = add_self_contact_terms_spread(
      add_contact_terms(
          add_spring_damping(gather_vertex_system(i, x, x_tilde, inv_h2, adj_offsets, adj, stretch, bend, tets), i, x,
                             x_start, inv_h, adj_offsets, adj, stretch),
          vs_xyz(x[i]), x[i].w, inv_h2, colliders, collider_count, ats_near_of(colliders, collider_count, near, i)),
      i, x, sc_tris, sc_edges, sc_inc, sc_n, sc_vt, sc_tv, sc_ee, sc_k, sc_r, sc_on);
  sys[4 * i] = (float4)(s.f.x, s.f.y, s.f.z, 0.0f);
  ATS_UNROLL for (int r = 0; r < 3; ++r) sys[4 * i + 1 + r] = (float4)(s.h.r[r].x, s.h.r[r].y, s.h.r[r].z, 0.0f);
}

static inline ats_mat3 sosd_block(__global const float4* sys, int i) {
  ats_mat3 h;
  ATS_UNROLL for (int r = 0; r < 3; ++r) h.r[r] = vs_xyz(sys[4 * i + 1 + r]);
  return h;
}

static inline void sosd_set_block(float* a, int stride, int row, int col, ats_mat3 h) {
  ATS_UNROLL for (int r = 0; r < 3; ++r) {
    a[(SOSD_MAX * (row + r) + col) * stride] = h.r[r].x;
    a[(SOSD_MAX * (row + r) + col + 1) * stride] = h.r[r].y;
    a[(SOSD_MAX * (row + r) + col + 2) * stride] = h.r[r].z;
  }
}

/* The stencil system over vertices v[0 .. n), off-diagonal blocks
 * off[p][q] (p < q; H_qp = H_pq^T): A's row r, column c at
 * a[(SOSD_MAX r + c) stride], f's row r at rhs[r stride], and whether
 * vertex p moves at movable[p stride]; a pinned vertex's rows are the
 * identity and its f 0. stride 1: one system (sosd_solve); 8: one lane of
 * sosd_bend_lanes' arrays, the pointers offset by the lane. */
ATS_FN_INLINE void sosd_fill(const int* v, int n, ats_mat3 off[4][4], __global const float4* x,
                             __global const float4* sys, float* a, float* rhs, int* movable, int stride) {
  const int m = 3 * n;
  ATS_UNROLL for (int p = 0; p < n; ++p) movable[p * stride] = x[v[p]].w != 0.0f;
  ATS_UNROLL for (int r = 0; r < m; ++r) {
    rhs[r * stride] = 0.0f;
    ATS_UNROLL for (int c = 0; c < m; ++c) a[(SOSD_MAX * r + c) * stride] = 0.0f;
  }
  ATS_UNROLL for (int p = 0; p < n; ++p) {
    if (!movable[p * stride]) {
      ATS_UNROLL for (int r = 0; r < 3; ++r) a[(SOSD_MAX + 1) * (3 * p + r) * stride] = 1.0f;
      continue;
    }
    const ats_vec3 f = vs_xyz(sys[4 * v[p]]);
    rhs[3 * p * stride] = f.x;
    rhs[(3 * p + 1) * stride] = f.y;
    rhs[(3 * p + 2) * stride] = f.z;
    sosd_set_block(a, stride, 3 * p, 3 * p, sosd_block(sys, v[p]));
    ATS_UNROLL for (int q = p + 1; q < n; ++q) {
      if (!movable[q * stride]) continue;
      sosd_set_block(a, stride, 3 * p, 3 * q, off[p][q]);
      sosd_set_block(a, stride, 3 * q, 3 * p, ats_m3_transpose(off[p][q]));
    }
  }
}

/* d[base + p] for the stencil's vertices: the solve's (rhs, stride apart)
 * where its Cholesky held (ok); otherwise each vertex's own block step, as
 * VBD would take it (a near-singular vertex block stays put); 0 for a
 * pinned vertex. */
ATS_FN_INLINE void sosd_write(const int* v, int n, int ok, const float* rhs, const int* movable, int stride,
                              __global const float4* sys, __global float4* d, int base) {
  ATS_UNROLL for (int p = 0; p < n; ++p) {
    float4 out = (float4)(0.0f);
    if (movable[p * stride]) {
      if (ok) {
        out = (float4)(rhs[3 * p * stride], rhs[(3 * p + 1) * stride], rhs[(3 * p + 2) * stride], 0.0f);
      } else {
        const ats_solve3 s = ats_m3_solve(sosd_block(sys, v[p]), vs_xyz(sys[4 * v[p]]));
        if (s.ok) out = (float4)(s.x.x, s.x.y, s.x.z, 0.0f);
      }
    }
    d[base + p] = out;
  }
}

/* Solves the stencil system over vertices v[0 .. n) (sosd_fill) and
 * writes d[base + p] (sosd_write): Cholesky when the system is positive
 * definite, else (an indefinite element coupling) each vertex's own block
 * step. Inlined into each kernel, where n is a constant (2 or 4), so the
 * unrolled loops keep the 3n x 3n system in registers: 1.2-1.8x as fast as
 * the call with its loops (docs/benchmarks.md, "SOSD's stencil solve
 * unrolled"), the same operations in the same order. */
ATS_FN_INLINE void sosd_solve(const int* v, int n, ats_mat3 off[4][4], __global const float4* x,
                              __global const float4* sys, __global float4* d, int base) {
  float a[SOSD_MAX][SOSD_MAX];
  float b[SOSD_MAX];
  int movable[4];
  const int m = 3 * n;
  sosd_fill(v, n, off, x, sys, &a[0][0], b, movable, 1);
  /* Cholesky A = L L^T in place (lower triangle), pivots checked against
   * the original diagonal so that scale does not matter. */
  int ok = 1;
  ATS_UNROLL for (int j = 0; j < m && ok; ++j) {
    const float diag = a[j][j];
    float s = diag;
    ATS_UNROLL for (int k = 0; k < j; ++k) s -= a[j][k] * a[j][k];
    if (!(s > 1e-6f * fabs(diag)) || !(diag > 0.0f)) {
      ok = 0;
      break;
    }
    const float l = sqrt(s);
    a[j][j] = l;
    ATS_UNROLL for (int r = j + 1; r < m; ++r) {
      float t = a[r][j];
      ATS_UNROLL for (int k = 0; k < j; ++k) t -= a[r][k] * a[j][k];
      a[r][j] = t / l;
    }
  }
  if (ok) {
    ATS_UNROLL for (int r = 0; r < m; ++r) { /* L y = b */
      float t = b[r];
      ATS_UNROLL for (int k = 0; k < r; ++k) t -= a[r][k] * b[k];
      b[r] = t / a[r][r];
    }
    ATS_UNROLL for (int r = m - 1; r >= 0; --r) { /* L^T d = y */
      float t = b[r];
      ATS_UNROLL for (int k = r + 1; k < m; ++k) t -= a[k][r] * b[k];
      b[r] = t / a[r][r];
    }
  }
  sosd_write(v, n, ok, b, movable, 1, sys, d, base);
}

ATS_TASK void sosd_stretch(int e, __global const float4* x, __global const float4* sys,
                           __global const ats_distance_c* stretch, __global float4* d, __global const float4* x_start,
                           float inv_h) {
  const ats_distance_c c = stretch[e];
  const int v[2] = {c.a, c.b};
  ats_mat3 off[4][4];
  ats_mat3 h_aa = ats_stretch_hessian(vs_xyz(x[c.a]), vs_xyz(x[c.b]), c.rest, 1.0f / c.compliance, 1);
  if (inv_h > 0.0f && c.damping > 0.0f) /* its damping term's block (common/energy_spring_damping.h) */
    h_aa = ats_m3_add(
        h_aa, ats_spring_damping_hessian(vs_xyz(x_start[c.a]), vs_xyz(x_start[c.b]), c.damping / c.compliance * inv_h));
  off[0][1] = ats_m3_scale(h_aa, -1.0f);
  sosd_solve(v, 2, off, x, sys, d, 2 * e);
}

/* A bending stencil's coupling blocks off[p][q] (p < q). */
static inline void sosd_bend_coupling(ats_bend_c c, __global const float4* x, ats_mat3 off[4][4]) {
  ats_vec3 y[4];
  ATS_UNROLL for (int j = 0; j < 4; ++j) y[j] = vs_xyz(x[c.v[j]]);
  ATS_UNROLL for (int p = 0; p < 4; ++p) {
    ATS_UNROLL for (int q = p + 1; q < 4; ++q) {
      off[p][q] = ats_bend_element_hessian(c.model, y, c.K, c.scale, 1.0f / c.compliance, p, q);
    }
  }
}

ATS_TASK void sosd_bend(int e, __global const float4* x, __global const float4* sys, __global const ats_bend_c* bend,
                        __global float4* d) {
  const ats_bend_c c = bend[e];
  ats_mat3 off[4][4];
  sosd_bend_coupling(c, x, off);
  sosd_solve(c.v, 4, off, x, sys, d, 4 * e);
}

/* solver.ordering: color_batches. Work-item b solves the bending stencils
 * order[8b .. 8b + 8) (solver/sosd/sosd_plan: each color block of
 * stencils padded to whole batches, -1 a padding lane) side by side: each
 * lane's 12 x 12 system is filled by sosd_fill, then the Cholesky and the
 * two substitutions run as 8-float vectors, lane l the operations
 * sosd_solve does for its stencil, in its order (a lane whose pivot fails
 * goes on with values nobody reads), and sosd_write writes each lane. The
 * same bits as sosd_bend. */
ATS_TASK void sosd_bend_lanes(int b, __global const float4* x, __global const float4* sys,
                              __global const ats_bend_c* bend, __global const int* order, __global float4* d) {
  float a[SOSD_MAX][SOSD_MAX][8];
  float rhs[SOSD_MAX][8];
  int movable[4][8];
  int e[8];
  ATS_UNROLL for (int l = 0; l < 8; ++l) e[l] = order[8 * b + l];
  for (int l = 0; l < 8; ++l) {
    if (e[l] < 0) { /* padding: the identity, solved and dropped */
      ATS_UNROLL for (int r = 0; r < SOSD_MAX; ++r) {
        rhs[r][l] = 0.0f;
        ATS_UNROLL for (int c = 0; c < SOSD_MAX; ++c) a[r][c][l] = r == c ? 1.0f : 0.0f;
      }
      continue;
    }
    const ats_bend_c c = bend[e[l]];
    ats_mat3 off[4][4];
    sosd_bend_coupling(c, x, off);
    sosd_fill(c.v, 4, off, x, sys, &a[0][0][l], &rhs[0][l], &movable[0][l], 8);
  }
  /* Cholesky A = L L^T in place, as sosd_solve, 8 lanes at a time. */
  int8 ok = (int8)(-1);
  ATS_UNROLL for (int j = 0; j < SOSD_MAX; ++j) {
    const float8 diag = vload8(0, a[j][j]);
    float8 s = diag;
    ATS_UNROLL for (int k = 0; k < j; ++k) {
      const float8 ajk = vload8(0, a[j][k]);
      s -= ajk * ajk;
    }
    ok &= (s > 1e-6f * fabs(diag)) & (diag > 0.0f);
    const float8 l = sqrt(s);
    vstore8(l, 0, a[j][j]);
    ATS_UNROLL for (int r = j + 1; r < SOSD_MAX; ++r) {
      float8 t = vload8(0, a[r][j]);
      ATS_UNROLL for (int k = 0; k < j; ++k) t -= vload8(0, a[r][k]) * vload8(0, a[j][k]);
      vstore8(t / l, 0, a[r][j]);
    }
  }
  ATS_UNROLL for (int r = 0; r < SOSD_MAX; ++r) { /* L y = b */
    float8 t = vload8(0, rhs[r]);
    ATS_UNROLL for (int k = 0; k < r; ++k) t -= vload8(0, a[r][k]) * vload8(0, rhs[k]);
    vstore8(t / vload8(0, a[r][r]), 0, rhs[r]);
  }
  ATS_UNROLL for (int r = SOSD_MAX - 1; r >= 0; --r) { /* L^T d = y */
    float8 t = vload8(0, rhs[r]);
    ATS_UNROLL for (int k = r + 1; k < SOSD_MAX; ++k) t -= vload8(0, a[k][r]) * vload8(0, rhs[k]);
    vstore8(t / vload8(0, a[r][r]), 0, rhs[r]);
  }
  int okl[8];
  vstore8(ok, 0, okl);
  for (int l = 0; l < 8; ++l) {
    if (e[l] < 0) continue;
    const ats_bend_c c = bend[e[l]];
    sosd_write(c.v, 4, okl[l], &rhs[0][l], &movable[0][l], 8, sys, d, 4 * e[l]);
  }
}

ATS_TASK void sosd_tet(int e, __global const float4* x, __global const float4* sys, __global const ats_tet_c* tets,
                       __global float4* d) {
  const ats_tet_c t = tets[e];
  ats_vec3 q[4];
  ATS_UNROLL for (int j = 0; j < 4; ++j) q[j] = vs_xyz(x[t.v[j]]);
  ats_mat3 dm;
  ATS_UNROLL for (int r = 0; r < 3; ++r) dm.r[r] = ats_v3(t.dm_inv[3 * r], t.dm_inv[3 * r + 1], t.dm_inv[3 * r + 2]);
  ats_mat3 off[4][4];
  ATS_UNROLL for (int p = 0; p < 4; ++p) {
    ATS_UNROLL for (int s = p + 1; s < 4; ++s) {
      off[p][s] = t.model == ATS_TET_STVK ? ats_tet_stvk_hessian(q, dm, t.volume, t.mu, t.lambda, p, s)
                                          : ats_tet_nh_hessian(q, dm, t.volume, t.mu, t.lambda, p, s);
    }
  }
  sosd_solve(t.v, 4, off, x, sys, d, 4 * e);
}

/* Stencil displacements of kind `main_kind`, elements [main_first,
 * main_end), take precedence (the main Gauss-Seidel block); main_kind = -1:
 * none. */
ATS_TASK void sosd_combine(int i, __global float4* x, __global const int* adj_offsets, __global const int* adj,
                           __global const float4* d_stretch, __global const float4* d_bend,
                           __global const float4* d_tet, __global const float4* sys, int main_kind, int main_first,
                           int main_end, float step, int has_ground, float ground,
                           __global const ats_collider_c* colliders, int collider_count,
                           __global const ats_mesh_near* near, int sc_on) {
  const float4 p = x[i];
  if (p.w == 0.0f) return;
  float4 sum = (float4)(0.0f);
  int n = 0;
  int has_main = 0;
  float4 main = (float4)(0.0f);
  for (int j = adj_offsets[i]; j < adj_offsets[i + 1]; ++j) {
    const int code = adj[j];
    const int e = code >> 4, kind = (code >> 2) & 3, slot = code & 3;
    const float4 dj = kind == 0 ? d_stretch[2 * e + slot] : kind == 1 ? d_bend[4 * e + slot] : d_tet[4 * e + slot];
    if (kind == main_kind && e >= main_first && e < main_end) {
      has_main = 1;
      main = dj;
    }
    sum += dj;
    ++n;
  }
  if (n == 0) return;
  float4 dx = step * (has_main ? main : sum / (float)n);
  if (has_ground && p.y + dx.y < ground) {
    /* a vertex pushed into the ground takes its own block's step with y
     * held there (as VBD does), not a projection of the stencils' step */
    const ats_mat3 h = sosd_block(sys, i);
    const ats_vec3 f = vs_xyz(sys[4 * i]);
    const ats_solve3 free_step = ats_m3_solve(h, f);
    const ats_vec3 s = ats_vertex_step_above_ground(h, f, free_step.x, p.y, ground);
    dx = (float4)(step * s.x, ground - p.y, step * s.z, 0.0f);
  }
  x[i] = sc_out_of_colliders((float4)(p.x + dx.x, p.y + dx.y, p.z + dx.z, p.w), colliders, collider_count,
                             ats_near_of(colliders, collider_count, near, i), sc_on);
}
