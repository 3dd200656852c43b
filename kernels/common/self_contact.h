/* Contact between simulated surfaces (cloth-cloth, self-collision,
 * cloth-solid): the narrow phase of a vertex-triangle or edge-edge pair and
 * its contact energy, as in Vertex Block Descent (Chen et al. 2024, §3.7,
 * after IPC): with d the distance between the two primitives and r the
 * contact thickness,
 *   E = 1/2 k (r - d)^2 for d < r, else 0.
 * A pair is four vertices q_j with weights w_j such that
 *   D = sum_j w_j q_j  (the vector from the closest point of the second
 *   primitive to the first), d = |D|, n = D / d,
 * so dE/dq_j = -k (r - d) w_j n, and the Gauss-Newton block of vertex j is
 * k w_j^2 n n^T (the weights held fixed). Vertex-triangle: w = (1, -b0,
 * -b1, -b2) with b the closest point's barycentric coordinates;
 * edge-edge: w = (1 - s, s, -(1 - t), -t).
 * In the common subset of C, C++ and OpenCL C: the kernels (float) and the
 * Newton reference (double, solver/energy/element_math.hpp) compile it. */
#ifndef ATS_SELF_CONTACT_H
#define ATS_SELF_CONTACT_H

#include "common/ats_math.h"
#include "common/energy_mat3.h"

typedef struct {
  ats_vec3 diff; /* sum_j w_j q_j */
  ats_real w[4];
  ats_real d; /* |diff| */
} ats_pair_geometry;

ATS_FN ats_pair_geometry ats_pair_of(ats_vec3 q0, ats_vec3 q1, ats_vec3 q2, ats_vec3 q3, ats_real w0, ats_real w1,
                                     ats_real w2, ats_real w3) {
  ats_pair_geometry g;
  g.w[0] = w0;
  g.w[1] = w1;
  g.w[2] = w2;
  g.w[3] = w3;
  g.diff = ats_add(ats_add(ats_scale(q0, w0), ats_scale(q1, w1)), ats_add(ats_scale(q2, w2), ats_scale(q3, w3)));
  g.d = ats_length(g.diff);
  return g;
}

/* Closest point of triangle (a, b, c) to p (Ericson 2005, Real-Time
 * Collision Detection §5.1.5); a degenerate triangle falls back to its
 * closest vertex or edge. */
ATS_FN ats_pair_geometry ats_point_triangle(ats_vec3 p, ats_vec3 a, ats_vec3 b, ats_vec3 c) {
  const ats_vec3 ab = ats_sub(b, a), ac = ats_sub(c, a), ap = ats_sub(p, a);
  const ats_real d1 = ats_dot(ab, ap), d2 = ats_dot(ac, ap);
  if (d1 <= 0 && d2 <= 0) return ats_pair_of(p, a, b, c, 1, -1, 0, 0);
  const ats_vec3 bp = ats_sub(p, b);
  const ats_real d3 = ats_dot(ab, bp), d4 = ats_dot(ac, bp);
  if (d3 >= 0 && d4 <= d3) return ats_pair_of(p, a, b, c, 1, 0, -1, 0);
  const ats_real vc = d1 * d4 - d3 * d2;
  if (vc <= 0 && d1 >= 0 && d3 <= 0) {
    const ats_real v = d1 / (d1 - d3);
    return ats_pair_of(p, a, b, c, 1, -(1 - v), -v, 0);
  }
  const ats_vec3 cp = ats_sub(p, c);
  const ats_real d5 = ats_dot(ab, cp), d6 = ats_dot(ac, cp);
  if (d6 >= 0 && d5 <= d6) return ats_pair_of(p, a, b, c, 1, 0, 0, -1);
  const ats_real vb = d5 * d2 - d1 * d6;
  if (vb <= 0 && d2 >= 0 && d6 <= 0) {
    const ats_real w = d2 / (d2 - d6);
    return ats_pair_of(p, a, b, c, 1, -(1 - w), 0, -w);
  }
  const ats_real va = d3 * d6 - d5 * d4;
  if (va <= 0 && (d4 - d3) >= 0 && (d5 - d6) >= 0) {
    const ats_real w = (d4 - d3) / ((d4 - d3) + (d5 - d6));
    return ats_pair_of(p, a, b, c, 1, 0, -(1 - w), -w);
  }
  const ats_real sum = va + vb + vc;
  if (!(sum > 0)) return ats_pair_of(p, a, b, c, 1, -1, 0, 0);
  const ats_real v = vb / sum, w = vc / sum;
  return ats_pair_of(p, a, b, c, 1, -(1 - v - w), -v, -w);
}

ATS_FN ats_real ats_clamp01(ats_real v) { return v < 0 ? (ats_real)0 : (v > 1 ? (ats_real)1 : v); }

/* Closest points of segments (p0, p1) and (q0, q1) (Ericson 2005 §5.1.9);
 * parallel segments take s = 0. */
ATS_FN ats_pair_geometry ats_edge_edge(ats_vec3 p0, ats_vec3 p1, ats_vec3 q0, ats_vec3 q1) {
  const ats_vec3 d1 = ats_sub(p1, p0), d2 = ats_sub(q1, q0), r = ats_sub(p0, q0);
  const ats_real a = ats_dot(d1, d1), e = ats_dot(d2, d2), f = ats_dot(d2, r);
  const ats_real eps = (ats_real)1e-20;
  ats_real s = 0, t = 0;
  if (a <= eps && e <= eps) {
    s = 0;
    t = 0;
  } else if (a <= eps) {
    t = ats_clamp01(f / e);
  } else {
    const ats_real c = ats_dot(d1, r);
    if (e <= eps) {
      s = ats_clamp01(-c / a);
    } else {
      const ats_real b = ats_dot(d1, d2);
      const ats_real denom = a * e - b * b;
      s = denom > (ats_real)1e-12 * a * e ? ats_clamp01((b * f - c * e) / denom) : (ats_real)0;
      t = (b * s + f) / e;
      if (t < 0) {
        t = 0;
        s = ats_clamp01(-c / a);
      } else if (t > 1) {
        t = 1;
        s = ats_clamp01((b - c) / a);
      }
    }
  }
  return ats_pair_of(p0, p1, q0, q1, 1 - s, s, -(1 - t), -t);
}

/* Sheet neighbours. A pair whose primitives are joined (a vertex of one
 * and a vertex of the other corners of one surface triangle) and whose
 * offset D lies within 30 degrees of the plane of its triangles is two
 * neighbours side by side in one sheet, held apart by the sheet's own
 * stretch: no contact. The same pair with D off that plane (the sheet
 * folded onto itself) is one. Whether D is within 30 degrees of the plane
 * of (a, b, c): (n . D)^2 < sin^2(30 deg) |n|^2 |D|^2, n = (b - a) x (c - a);
 * a degenerate triangle or D = 0 has no such angle: not in the plane. */
ATS_FN ats_vec3 ats_plane_normal(ats_vec3 a, ats_vec3 b, ats_vec3 c) {
  return ats_v3_cross(ats_sub(b, a), ats_sub(c, a));
}
ATS_FN int ats_in_plane_of(ats_vec3 diff, ats_vec3 n) {
  const ats_real dn = ats_dot(n, diff);
  return dn * dn < (ats_real)0.25 * ats_dot(n, n) * ats_dot(diff, diff);
}
ATS_FN int ats_pair_in_plane(ats_vec3 diff, ats_vec3 a, ats_vec3 b, ats_vec3 c) {
  return ats_in_plane_of(diff, ats_plane_normal(a, b, c));
}

/* The pair's contact energy (see above). */
ATS_FN ats_real ats_pair_energy(ats_pair_geometry g, ats_real k, ats_real r) {
  if (!(g.d < r)) return 0;
  const ats_real gap = r - g.d;
  return (ats_real)0.5 * k * gap * gap;
}

/* The unit normal n = D / d; zero when the primitives touch exactly (no
 * direction to push along). */
ATS_FN ats_vec3 ats_pair_normal(ats_pair_geometry g) {
  return g.d > (ats_real)1e-12 ? ats_scale(g.diff, 1 / g.d) : ats_v3(0, 0, 0);
}

/* dE/dq_j of the pair's vertex in slot j. */
ATS_FN ats_vec3 ats_pair_gradient(ats_pair_geometry g, ats_real k, ats_real r, int j) {
  if (!(g.d < r)) return ats_v3(0, 0, 0);
  return ats_scale(ats_pair_normal(g), -k * (r - g.d) * g.w[j]);
}

/* Gauss-Newton block of slots (i, j): k w_i w_j n n^T. */
ATS_FN ats_mat3 ats_pair_hessian(ats_pair_geometry g, ats_real k, ats_real r, int i, int j) {
  if (!(g.d < r)) return ats_m3_diag(0);
  const ats_vec3 n = ats_pair_normal(g);
  return ats_m3_scale(ats_m3_outer(n, n), k * g.w[i] * g.w[j]);
}

#endif
