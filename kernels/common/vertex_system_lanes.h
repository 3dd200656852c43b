/* The vertex-system gather of common/vertex_system.h for 8 vertices at once,
 * as 8 float lanes (VBD's solver.ordering: color_batches, JPGD's
 * vertex_batches): lane l gathers vertex v[l] (-1: a padding lane, at the
 * end of a batch; its sums are not used). VBD's 8 vertices come from one
 * color, so no lane reads a position another lane's step writes; JPGD's
 * are 8 consecutive vertices, which read x^k and write x^{k+1}.
 * ats_m3_solve8 then solves the 8 systems as lanes with ats_m3_solve's
 * operations.
 *
 * Each lane sums its elements in its own adjacency order with the scalar
 * gather's operations, so each lane's system is bit for bit the scalar
 * one. The lanes walk their lists in three phases, the entries of one kind
 * each (a vertex's list holds its stretch entries, then its bending, then
 * its tets: solver/vertex/vertex_layout.cpp): a lane whose next entry is of
 * another kind waits for the next phase. Springs and isometric bending run
 * as 8-float vectors; a dihedral stencil or a tet is computed lane by lane
 * with the scalar math and added as a vector.
 *
 * In the common subset of OpenCL C and GCC's C++ (vector extensions): the
 * kernels (kernels/vbd/vbd.cl, kernels/jpgd/jpgd.cl) and the host VBD reference's lanes
 * (lib/solver/vbd/vbd_reference.cpp, bench_native's native lanes row) run
 * this one gather. Needs FP contraction off, as energy_stretch.h does. */
#ifndef ATS_VERTEX_SYSTEM_LANES_H
#define ATS_VERTEX_SYSTEM_LANES_H

#include "common/vertex_solve.h"
#include "common/vertex_system.h"

#ifdef __OPENCL_VERSION__
typedef float8 ats_f8;
typedef int8 ats_i8;
#define ATS_F8(s) ((float8)(s))
#define ATS_F8_LOAD(p) vload8(0, p)
#define ATS_I8_LOAD(p) vload8(0, p)
#define ATS_F8_STORE(v, p) vstore8(v, 0, p)
#define ATS_F8_SQRT(v) sqrt(v)
#define ATS_F8_FMA(a, b, c) fma(a, b, c)
#define ATS_F8_SELECT(m, a, b) select(b, a, m) /* a where m, else b */
#define ATS_F8_FMAX(a, b) fmax(a, b)
#define ATS_F8_FABS(a) fabs(a)
#else
typedef float ats_f8 __attribute__((vector_size(32)));
typedef int ats_i8 __attribute__((vector_size(32)));
#define ATS_F8(s) (ats_f8{(s), (s), (s), (s), (s), (s), (s), (s)})
#define ATS_F8_LOAD(p) ats_f8_load(p)
#define ATS_I8_LOAD(p) ats_i8_load(p)
#define ATS_F8_STORE(v, p) __builtin_memcpy(p, &(v), sizeof(ats_f8))
#define ATS_F8_SQRT(v) ats_f8_sqrt(v)
#define ATS_F8_FMA(a, b, c) ats_f8_fma(a, b, c)
#define ATS_F8_SELECT(m, a, b) ((m) ? (a) : (b))
#define ATS_F8_FMAX(a, b) ats_f8_fmax(a, b)
#define ATS_F8_FABS(a) ats_f8_fabs(a)
ATS_FN ats_f8 ats_f8_load(const float* p) {
  ats_f8 v;
  __builtin_memcpy(&v, p, sizeof v);
  return v;
}
ATS_FN ats_i8 ats_i8_load(const int* p) {
  ats_i8 v;
  __builtin_memcpy(&v, p, sizeof v);
  return v;
}
ATS_FN ats_f8 ats_f8_sqrt(ats_f8 v) {
  for (int l = 0; l < 8; ++l) v[l] = __builtin_sqrtf(v[l]);
  return v;
}
ATS_FN ats_f8 ats_f8_fmax(ats_f8 a, ats_f8 b) {
  for (int l = 0; l < 8; ++l) a[l] = __builtin_fmaxf(a[l], b[l]);
  return a;
}
ATS_FN ats_f8 ats_f8_fabs(ats_f8 a) {
  for (int l = 0; l < 8; ++l) a[l] = __builtin_fabsf(a[l]);
  return a;
}
ATS_FN ats_f8 ats_f8_fma(ats_f8 a, ats_f8 b, ats_f8 c) {
  for (int l = 0; l < 8; ++l) a[l] = __builtin_fmaf(a[l], b[l], c[l]);
  return a;
}
#endif

/* ats_two_sum and ats_stretch_extension (common/energy_stretch.h), lane-wise. */
ATS_FN ats_f8 ats_two_sum8(ats_f8 a, ats_f8 b, ats_f8* e) {
  const ats_f8 s = a + b;
  const ats_f8 z = s - a;
  *e = (a - (s - z)) + (b - z);
  return s;
}
ATS_FN ats_f8 ats_add_square8(ats_f8 s, ats_f8 a, ats_f8* err) {
  const ats_f8 p = a * a;
  const ats_f8 e_prod = ATS_F8_FMA(a, a, -p);
  ats_f8 e_sum;
  s = ats_two_sum8(s, p, &e_sum);
  *err += e_prod + e_sum;
  return s;
}
ATS_FN ats_f8 ats_stretch_extension8(const ats_f8 xa[3], const ats_f8 xb[3], ats_f8 rest, ats_f8 l) {
  ats_f8 err = ATS_F8(0.0f), d[3], a[3];
  ATS_UNROLL for (int j = 0; j < 3; ++j) a[j] = ats_two_sum8(xa[j], -xb[j], &d[j]);
  ats_f8 s = ats_add_square8(ATS_F8(0.0f), a[0], &err);
  s = ats_add_square8(s, a[1], &err);
  s = ats_add_square8(s, a[2], &err);
  const ats_f8 p = rest * -rest;
  const ats_f8 e_prod = ATS_F8_FMA(rest, -rest, -p);
  ats_f8 e_sum;
  s = ats_two_sum8(s, p, &e_sum);
  err += e_prod + e_sum;
  err += 2.0f * (a[0] * d[0] + a[1] * d[1] + a[2] * d[2]);
  return ATS_F8_SELECT(l + rest <= 0.0f, ATS_F8(0.0f), (s + err) / (l + rest));
}

/* One phase's contribution: f -= g (f += g where plus), h += H, in the
 * lanes that take an entry. acc: f.x, f.y, f.z, then h row by row. */
ATS_FN void ats_vs8_add(ats_f8 acc[12], ats_i8 take, ats_i8 plus, const ats_f8 g[3], const ats_f8 hc[9]) {
  ATS_UNROLL for (int j = 0; j < 3; ++j) acc[j] =
      ATS_F8_SELECT(take, ATS_F8_SELECT(plus, acc[j] + g[j], acc[j] - g[j]), acc[j]);
  ATS_UNROLL for (int j = 0; j < 9; ++j) acc[3 + j] = ATS_F8_SELECT(take, acc[3 + j] + hc[j], acc[3 + j]);
}

/* ats_stretch_gradient and ats_stretch_hessian (projected), lane-wise. */
ATS_FN void ats_stretch_terms8(const ats_f8 xa[3], const ats_f8 xb[3], ats_f8 rest, ats_f8 k, ats_f8 g[3],
                               ats_f8 hc[9]) {
  ats_f8 d[3];
  ATS_UNROLL for (int j = 0; j < 3; ++j) d[j] = xa[j] - xb[j];
  const ats_f8 l = ATS_F8_SQRT(d[0] * d[0] + d[1] * d[1] + d[2] * d[2]);
  const ats_i8 live = l > ATS_STRETCH_MIN_LENGTH;
  const ats_f8 ext = ats_stretch_extension8(xa, xb, rest, l);
  const ats_f8 gs = k * ext / l;
  const ats_f8 inv_l = 1.0f / l;
  ats_f8 n[3];
  ATS_UNROLL for (int j = 0; j < 3; ++j) {
    g[j] = ATS_F8_SELECT(live, d[j] * gs, ATS_F8(0.0f));
    n[j] = d[j] * inv_l;
  }
  ats_f8 f = ext / l;
  f = ATS_F8_SELECT(f < 0.0f, ATS_F8(0.0f), f);
  const ats_f8 across = k * (1.0f - f), diag = k * f;
  ATS_UNROLL for (int r = 0; r < 3; ++r) {
    ATS_UNROLL for (int c = 0; c < 3; ++c) {
      const ats_f8 o = n[c] * across * n[r];
      hc[3 * r + c] = ATS_F8_SELECT(live, r == c ? o + diag : o + 0.0f, ATS_F8(0.0f));
    }
  }
}

/* A lane's scalar contribution (vertex_system.h's arithmetic for a dihedral
 * stencil or a tet) into the per-lane arrays the phase loads as vectors. */
ATS_FN void ats_vs8_put(float g[3][8], float hc[9][8], int l, ats_vec3 gv, ats_mat3 hm) {
  g[0][l] = gv.x;
  g[1][l] = gv.y;
  g[2][l] = gv.z;
  ATS_UNROLL for (int r = 0; r < 3; ++r) {
    hc[3 * r][l] = hm.r[r].x;
    hc[3 * r + 1][l] = hm.r[r].y;
    hc[3 * r + 2][l] = hm.r[r].z;
  }
}

/* A dihedral stencil's and a tet's terms for one lane, with the scalar
 * math, kept out of line: the lanes' loop holds one call, not eight copies
 * of the rarely taken math. */
ATS_FN_NOINLINE void ats_vs8_bend_lane(ATS_GLOBAL const ats_float4* x, ATS_GLOBAL const ats_bend_c* bend, int code,
                                       float g[3][8], float hc[9][8], int l) {
  const ats_bend_c c = bend[code >> 4];
  const int slot = code & 3;
  const float stiffness = 1.0f / c.compliance;
  ats_vec3 q[4];
  ATS_UNROLL for (int j = 0; j < 4; ++j) q[j] = vs_xyz(x[c.v[j]]);
  ats_vs8_put(g, hc, l, ats_bend_element_gradient(c.model, q, c.K, c.scale, stiffness, c.rest_angle, slot),
              ats_bend_element_hessian(c.model, q, c.K, c.scale, stiffness, slot, slot));
}
ATS_FN_NOINLINE void ats_vs8_tet_lane(ATS_GLOBAL const ats_float4* x, ATS_GLOBAL const ats_tet_c* tets, int code,
                                      float g[3][8], float hc[9][8], int l) {
  const ats_tet_c t = tets[code >> 4];
  const int slot = code & 3;
  ats_vec3 q[4];
  ATS_UNROLL for (int j = 0; j < 4; ++j) q[j] = vs_xyz(x[t.v[j]]);
  ats_mat3 dm;
  ATS_UNROLL for (int r = 0; r < 3; ++r) dm.r[r] = ats_v3(t.dm_inv[3 * r], t.dm_inv[3 * r + 1], t.dm_inv[3 * r + 2]);
  if (t.model == ATS_TET_STVK) {
    ats_vs8_put(g, hc, l, ats_tet_stvk_gradient(q, dm, t.volume, t.mu, t.lambda, slot),
                ats_tet_stvk_hessian_diag_psd(q, dm, t.volume, t.mu, t.lambda, slot));
  } else {
    ats_vs8_put(g, hc, l, ats_tet_nh_gradient(q, dm, t.volume, t.mu, t.lambda, slot),
                ats_tet_nh_hessian_diag_psd(q, dm, t.volume, t.mu, t.lambda, slot));
  }
}

/* The 8 systems as 12 vectors: f.x, f.y, f.z, then h row by row. */
ATS_FN void gather_vertex_system8_lanes(const int v[8], ATS_GLOBAL const ats_float4* x,
                                        ATS_GLOBAL const ats_float4* x_tilde, float inv_h2,
                                        ATS_GLOBAL const int* adj_offsets, ATS_GLOBAL const int* adj,
                                        ATS_GLOBAL const ats_distance_c* stretch, ATS_GLOBAL const ats_bend_c* bend,
                                        ATS_GLOBAL const ats_tet_c* tets, ats_f8 acc[12]) {
  float a0[12][8];
  int at[8], end[8];
  ATS_UNROLL for (int l = 0; l < 8; ++l) {
    const int i = v[l];
    at[l] = i >= 0 ? adj_offsets[i] : 0;
    end[l] = i >= 0 ? adj_offsets[i + 1] : 0;
    const ats_float4 p = x[i >= 0 ? i : v[0]];
    const float mass = 1.0f / p.w;
    const ats_vec3 f =
        ats_scale(ats_inertia_gradient(vs_xyz(p), vs_xyz(x_tilde[i >= 0 ? i : v[0]]), mass, inv_h2), -1.0f);
    const ats_mat3 h = ats_inertia_hessian(mass, inv_h2);
    ats_vs8_put(a0, a0 + 3, l, f, h);
  }
  ATS_UNROLL for (int j = 0; j < 12; ++j) acc[j] = ATS_F8_LOAD(a0[j]);
  for (int kind = 0; kind < 3; ++kind) {
    for (;;) {
      int take[8], code[8], pl[8], any = 0;
      ATS_UNROLL for (int l = 0; l < 8; ++l) {
        code[l] = at[l] < end[l] ? adj[at[l]] : -1;
        take[l] = code[l] >= 0 && ((code[l] >> 2) & 3) == kind ? -1 : 0;
        at[l] += take[l] ? 1 : 0;
        any |= take[l];
      }
      if (!any) break;
      ats_f8 g[3], hc[9];
      ATS_UNROLL for (int l = 0; l < 8; ++l) pl[l] = 0;
      if (kind == 0) {
        float ax[3][8], bx[3][8], rest[8], comp[8];
        ATS_UNROLL for (int l = 0; l < 8; ++l) {
          /* a lane that takes nothing gathers a unit spring at rest: finite, and its sums are not taken */
          const ats_distance_c c = stretch[take[l] ? code[l] >> 4 : 0];
          const ats_float4 pa = x[take[l] ? c.a : v[0]];
          const ats_float4 pb = take[l] ? x[c.b] : pa;
          ax[0][l] = pa.x;
          ax[1][l] = pa.y;
          ax[2][l] = pa.z;
          bx[0][l] = take[l] ? pb.x : pa.x + 1.0f;
          bx[1][l] = pb.y;
          bx[2][l] = pb.z;
          rest[l] = take[l] ? c.rest : 1.0f;
          comp[l] = take[l] ? c.compliance : 1.0f;
          pl[l] = take[l] && (code[l] & 3) != 0 ? -1 : 0;
        }
        ats_f8 xa[3], xb[3];
        ATS_UNROLL for (int j = 0; j < 3; ++j) {
          xa[j] = ATS_F8_LOAD(ax[j]);
          xb[j] = ATS_F8_LOAD(bx[j]);
        }
        ats_stretch_terms8(xa, xb, ATS_F8_LOAD(rest), 1.0f / ATS_F8_LOAD(comp), g, hc);
      } else if (kind == 1) {
        /* isometric: g = S (k s K_slot), H = diag(k s K_slot K_slot), S = sum_j K_j x_j */
        float q[4][3][8], kk[4][8], comp[8], scale[8], kslot[8], gd[3][8], hd[9][8];
        int isom[8], dihedral = 0;
        ATS_UNROLL for (int l = 0; l < 8; ++l) {
          const ats_bend_c c = bend[take[l] ? code[l] >> 4 : 0];
          const int iso = take[l] && c.model != ATS_BEND_DIHEDRAL;
          isom[l] = iso ? -1 : 0;
          ATS_UNROLL for (int j = 0; j < 4; ++j) {
            const ats_float4 p = x[iso ? c.v[j] : v[0]];
            q[j][0][l] = p.x;
            q[j][1][l] = p.y;
            q[j][2][l] = p.z;
            kk[j][l] = iso ? c.K[j] : 0.0f;
          }
          comp[l] = iso ? c.compliance : 1.0f;
          scale[l] = iso ? c.scale : 0.0f;
          kslot[l] = iso ? c.K[code[l] & 3] : 0.0f;
          if (take[l] && !iso) {
            if (!dihedral) {
              ATS_UNROLL for (int m = 0; m < 8; ++m) ats_vs8_put(gd, hd, m, ats_v3(0, 0, 0), ats_m3_diag(0));
            }
            dihedral = 1;
            ats_vs8_bend_lane(x, bend, code[l], gd, hd, l);
          }
        }
        ats_f8 s[3];
        ATS_UNROLL for (int j = 0; j < 3; ++j) {
          s[j] = ATS_F8(0.0f);
          ATS_UNROLL for (int m = 0; m < 4; ++m) s[j] = s[j] + ATS_F8_LOAD(q[m][j]) * ATS_F8_LOAD(kk[m]);
        }
        const ats_f8 kslv = ATS_F8_LOAD(kslot);
        const ats_f8 gs = 1.0f / ATS_F8_LOAD(comp) * ATS_F8_LOAD(scale) * kslv, hd8 = gs * kslv;
        ATS_UNROLL for (int j = 0; j < 3; ++j) g[j] = s[j] * gs;
        ATS_UNROLL for (int j = 0; j < 9; ++j) hc[j] = (j == 0 || j == 4 || j == 8) ? hd8 : ATS_F8(0.0f);
        if (dihedral) {
          const ats_i8 iso = ATS_I8_LOAD(isom);
          ATS_UNROLL for (int j = 0; j < 3; ++j) g[j] = ATS_F8_SELECT(iso, g[j], ATS_F8_LOAD(gd[j]));
          ATS_UNROLL for (int j = 0; j < 9; ++j) hc[j] = ATS_F8_SELECT(iso, hc[j], ATS_F8_LOAD(hd[j]));
        }
      } else {
        float gd[3][8], hd[9][8];
        ATS_UNROLL for (int l = 0; l < 8; ++l) {
          if (!take[l]) {
            ats_vs8_put(gd, hd, l, ats_v3(0, 0, 0), ats_m3_diag(0));
            continue;
          }
          ats_vs8_tet_lane(x, tets, code[l], gd, hd, l);
        }
        ATS_UNROLL for (int j = 0; j < 3; ++j) g[j] = ATS_F8_LOAD(gd[j]);
        ATS_UNROLL for (int j = 0; j < 9; ++j) hc[j] = ATS_F8_LOAD(hd[j]);
      }
      ats_vs8_add(acc, ATS_I8_LOAD(take), ATS_I8_LOAD(pl), g, hc);
    }
  }
}

/* Lane l of the 8 systems acc (gather_vertex_system8_lanes). */
ATS_FN vertex_system ats_vs8_lane(const ats_f8 acc[12], int l) {
  vertex_system s;
  s.f = ats_v3(acc[0][l], acc[1][l], acc[2][l]);
  ATS_UNROLL for (int r = 0; r < 3; ++r) s.h.r[r] = ats_v3(acc[3 + 3 * r][l], acc[4 + 3 * r][l], acc[5 + 3 * r][l]);
  return s;
}

/* The same systems, one per lane. */
ATS_FN void gather_vertex_system8(const int v[8], ATS_GLOBAL const ats_float4* x, ATS_GLOBAL const ats_float4* x_tilde,
                                  float inv_h2, ATS_GLOBAL const int* adj_offsets, ATS_GLOBAL const int* adj,
                                  ATS_GLOBAL const ats_distance_c* stretch, ATS_GLOBAL const ats_bend_c* bend,
                                  ATS_GLOBAL const ats_tet_c* tets, vertex_system out[8]) {
  ats_f8 acc[12];
  gather_vertex_system8_lanes(v, x, x_tilde, inv_h2, adj_offsets, adj, stretch, bend, tets, acc);
  ATS_UNROLL for (int l = 0; l < 8; ++l) out[l] = ats_vs8_lane(acc, l);
}

/* ats_m3_solve (common/vertex_solve.h) lane-wise: dx = H^-1 f of each lane's
 * system acc (gather_vertex_system8_lanes), and where it was solved. */
ATS_FN ats_i8 ats_m3_solve8(const ats_f8 acc[12], ats_f8 dx[3]) {
  ats_f8 m = ATS_F8(0.0f);
  ATS_UNROLL for (int r = 0; r < 3; ++r) {
    m = ATS_F8_FMAX(m, ATS_F8_FMAX(ATS_F8_FABS(acc[3 + 3 * r]),
                                   ATS_F8_FMAX(ATS_F8_FABS(acc[4 + 3 * r]), ATS_F8_FABS(acc[5 + 3 * r]))));
  }
  const ats_f8 inv_m = 1.0f / m;
  ats_f8 h[9];
  ATS_UNROLL for (int j = 0; j < 9; ++j) h[j] = acc[3 + j] * inv_m;
  /* c0 = r1 x r2, c1 = r2 x r0, c2 = r0 x r1 (ats_v3_cross) */
  ats_f8 c[3][3];
  ATS_UNROLL for (int k = 0; k < 3; ++k) {
    const int a = 3 * ((k + 1) % 3), b = 3 * ((k + 2) % 3);
    c[k][0] = h[a + 1] * h[b + 2] - h[a + 2] * h[b + 1];
    c[k][1] = h[a + 2] * h[b + 0] - h[a + 0] * h[b + 2];
    c[k][2] = h[a + 0] * h[b + 1] - h[a + 1] * h[b + 0];
  }
  const ats_f8 det = h[0] * c[0][0] + h[1] * c[0][1] + h[2] * c[0][2];
  const ats_i8 ok = (m > 0.0f) & (ATS_F8_FABS(det) > 1e-6f);
  const ats_f8 s = inv_m / det;
  ATS_UNROLL for (int j = 0; j < 3; ++j) {
    dx[j] = ATS_F8_SELECT(ok, ((c[0][j] * acc[0] + c[1][j] * acc[1]) + c[2][j] * acc[2]) * s, ATS_F8(0.0f));
  }
  return ok;
}

/* Lane l of ats_m3_solve8's result as ats_m3_solve returns it (a lane it
 * could not solve has dx 0 there too). */
ATS_FN ats_solve3 ats_solve8_lane(ats_i8 ok, const ats_f8 dx[3], int l) {
  ats_solve3 d;
  d.ok = ok[l] ? 1 : 0;
  d.x = ats_v3(dx[0][l], dx[1][l], dx[2][l]);
  return d;
}

/* Whether a vertex's solve takes its gathered system as it is: no surface
 * contact, collider or spring damping term is added after the gather. The
 * lanes kernels (VBD's, JPGD's) then solve their 8 systems as lanes too. */
ATS_FN int ats_gather_alone(int contact_on, int collider_count, float inv_h) {
  return !contact_on && collider_count == 0 && !(inv_h > 0.0f);
}

/* VBD's vertex step where no contact term and no damping follows the gather
 * (vbd_step in kernels/vbd/vbd.cl, the host reference's step_vertex): the 8
 * solves as lanes, then each lane's ground and its write. */
ATS_FN void ats_vbd_step8(const int v[8], const ats_f8 acc[12], ATS_GLOBAL ats_float4* x, int has_ground,
                          float ground) {
  ats_f8 dx[3];
  const ats_i8 ok = ats_m3_solve8(acc, dx);
  for (int l = 0; l < 8; ++l) {
    if (v[l] < 0 || !ok[l]) continue;
    const ats_float4 p = x[v[l]];
    ats_vec3 step = ats_v3(dx[0][l], dx[1][l], dx[2][l]);
    if (has_ground && p.y + step.y < ground) {
      const vertex_system s = ats_vs8_lane(acc, l);
      step = ats_vertex_step_above_ground(s.h, s.f, step, p.y, ground);
    }
    x[v[l]].x = p.x + step.x;
    x[v[l]].y = p.y + step.y;
    x[v[l]].z = p.z + step.z;
  }
}

#endif
