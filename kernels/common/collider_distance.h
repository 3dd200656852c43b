/* Signed distance of a point to an analytic collider's surface and the
 * contact energy built on it, in the common subset of C, C++ and OpenCL C
 * (ats_real: float in kernels, double in the Newton reference).
 *
 * The gap of a particle is g = phi(x) - thickness (phi: signed distance,
 * negative inside). The contact energy of a particle of mass m is the
 * quadratic penalty of the VBD paper (Chen et al. 2024, §3.5, Eq. 17),
 *   E_c = 1/2 k min(g, 0)^2,  k = stiffness m / h^2,
 * its gradient k g n (n = grad phi, the outward normal) and its Gauss-Newton
 * Hessian k n n^T (the curvature term k g grad^2 phi is dropped: it keeps
 * the block positive semi-definite). */
#ifndef ATS_COLLIDER_DISTANCE_H
#define ATS_COLLIDER_DISTANCE_H

#include "common/ats_math.h"
#include "common/collider_types.h"
#include "common/energy_mat3.h"
#include "common/mesh_near.h"
#include "common/surface_distance.h"

ATS_FN_INLINE ats_vec3 ats_collider_vec(ATS_GLOBAL const float* v) { return ats_v3(v[0], v[1], v[2]); }

/* A normal for a point at the centre of a sphere or on a capsule's axis. */
ATS_FN_INLINE ats_surface_distance ats_radial_distance(ats_vec3 d, ats_real radius) {
  ats_surface_distance s;
  const ats_real len = ats_length(d);
  s.phi = len - radius;
  s.n = len > (ats_real)0 ? ats_scale(d, (ats_real)1 / len) : ats_v3(0, 1, 0);
  return s;
}

ATS_FN_INLINE ats_surface_distance ats_box_distance(ATS_GLOBAL const ats_collider_c* c, ats_vec3 x) {
  const ats_vec3 d = ats_sub(x, ats_collider_vec(c->c));
  ats_vec3 axis[3];
  ats_real p[3], q[3], h[3];
  ATS_UNROLL for (int k = 0; k < 3; ++k) {
    axis[k] = ats_collider_vec(c->axes + 4 * k);
    p[k] = ats_dot(d, axis[k]);
    h[k] = c->extent[k];
    q[k] = fabs(p[k]) - h[k];
  }
  ats_surface_distance s;
  if (q[0] > 0 || q[1] > 0 || q[2] > 0) { /* outside: distance to the nearest point of the box */
    ats_vec3 out = ats_v3(0, 0, 0);
    ATS_UNROLL for (int k = 0; k < 3; ++k) {
      if (q[k] > 0) out = ats_add(out, ats_scale(axis[k], p[k] < 0 ? -q[k] : q[k]));
    }
    s.phi = ats_length(out);
    s.n = ats_scale(out, (ats_real)1 / s.phi);
    return s;
  }
  int k = 0; /* inside: the nearest face */
  if (q[1] > q[k]) k = 1;
  if (q[2] > q[k]) k = 2;
  s.phi = q[k];
  s.n = ats_scale(axis[k], p[k] < 0 ? (ats_real)-1 : (ats_real)1);
  return s;
}

/* A particle's near lists (common/mesh_near.h), one per mesh collider, or
 * null (the mesh's tree is walked): particle i's of the buffer `near`. */
ATS_FN_INLINE ATS_GLOBAL const ats_mesh_near* ats_near_of(ATS_GLOBAL const ats_collider_c* colliders, int count,
                                                          ATS_GLOBAL const ats_mesh_near* near, int i) {
  if (count == 0 || near == 0) return 0;
  return near + i * (int)colliders[0].near_slots;
}

/* The signed distance of x to collider c; `near`: the particle's near
 * lists (ats_near_of), or null. */
ATS_FN_INLINE ats_surface_distance ats_collider_distance_near(ATS_GLOBAL const ats_collider_c* c, ats_vec3 x,
                                                              ATS_GLOBAL const ats_mesh_near* near) {
  const int shape = (int)c->shape;
  if (shape == ATS_COLLIDER_PLANE) {
    ats_surface_distance s;
    s.n = ats_collider_vec(c->n);
    s.phi = ats_dot(ats_sub(x, ats_collider_vec(c->c)), s.n);
    return s;
  }
  if (shape == ATS_COLLIDER_SPHERE) return ats_radial_distance(ats_sub(x, ats_collider_vec(c->c)), c->radius);
  if (shape == ATS_COLLIDER_CAPSULE) {
    const ats_vec3 a = ats_collider_vec(c->c);
    const ats_vec3 ab = ats_sub(ats_collider_vec(c->n), a);
    const ats_real len2 = ats_dot(ab, ab);
    ats_real t = len2 > (ats_real)0 ? ats_dot(ats_sub(x, a), ab) / len2 : (ats_real)0;
    t = fmin(fmax(t, (ats_real)0), (ats_real)1);
    return ats_radial_distance(ats_sub(x, ats_add(a, ats_scale(ab, t))), c->radius);
  }
  if (shape == ATS_COLLIDER_MESH)
    return ats_mesh_distance_near(c, x, c->mesh[3], near == 0 ? near : near + (int)c->near_slot);
  return ats_box_distance(c, x);
}

ATS_FN_INLINE ats_surface_distance ats_collider_distance(ATS_GLOBAL const ats_collider_c* c, ats_vec3 x) {
  return ats_collider_distance_near(c, x, 0);
}

/* The gap g = phi - thickness (negative: the particle is inside the
 * collider's thickened surface) and the normal. */
ATS_FN_INLINE ats_surface_distance ats_collider_gap_near(ATS_GLOBAL const ats_collider_c* c, ats_vec3 x,
                                                         ATS_GLOBAL const ats_mesh_near* near) {
  ats_surface_distance s = ats_collider_distance_near(c, x, near);
  s.phi -= c->thickness;
  return s;
}
ATS_FN_INLINE ats_surface_distance ats_collider_gap(ATS_GLOBAL const ats_collider_c* c, ats_vec3 x) {
  return ats_collider_gap_near(c, x, 0);
}

/* Whether x is certainly outside collider c's thickened surface, by a test
 * cheaper than its distance (no square root, no division): past
 * (radius + thickness)^2 in squared distance, with a margin of 1e-4, far
 * above the rounding of the distance, so that where it says so the gap is
 * positive and the caller's result is the one the gap would have given.
 * A sphere: from its centre. A capsule: from an end where x projects
 * beyond it, else from the axis, times |b - a|^2 (its rounding, from
 * cancellation when x is near the axis far from an end, bounded by 1e-6 of
 * the terms and subtracted). Other shapes: never (their distance is taken). */
ATS_FN_INLINE int ats_collider_clear(ATS_GLOBAL const ats_collider_c* c, ats_vec3 x) {
  const int shape = (int)c->shape;
  const ats_real reach = c->radius + c->thickness;
  const ats_real reach2 = (ats_real)1.0001 * reach * reach;
  const ats_vec3 u = ats_sub(x, ats_collider_vec(c->c));
  if (shape == ATS_COLLIDER_SPHERE) return ats_dot(u, u) > reach2;
  if (shape != ATS_COLLIDER_CAPSULE) return 0;
  const ats_vec3 ab = ats_sub(ats_collider_vec(c->n), ats_collider_vec(c->c));
  const ats_real len2 = ats_dot(ab, ab), p = ats_dot(u, ab), uu = ats_dot(u, u);
  if (p <= 0) return uu > reach2;
  if (p >= len2) {
    const ats_vec3 w = ats_sub(u, ab);
    return ats_dot(w, w) > reach2;
  }
  return uu * len2 - p * p - (ats_real)1e-6 * uu * len2 > reach2 * len2;
}

/* A particle counts as touching a collider when its gap is below 1 % of
 * the thickness (projected particles sit at gap 0 up to rounding). */
ATS_FN int ats_collider_touching(ATS_GLOBAL const ats_collider_c* c, ats_real gap) {
  return gap <= (ats_real)0.01 * c->thickness;
}

ATS_FN ats_real ats_contact_energy(ATS_GLOBAL const ats_collider_c* c, ats_vec3 x, ats_real mass, ats_real inv_h2) {
  const ats_surface_distance s = ats_collider_gap(c, x);
  if (!(s.phi < 0)) return 0;
  return (ats_real)0.5 * c->stiffness * mass * inv_h2 * s.phi * s.phi;
}

/* The penalty's gradient and Gauss-Newton block from a gap s already
 * taken (k = stiffness * mass / h^2): a vertex method's contact terms take
 * the gap once for both (vertex_contact.h), as a mesh collider's gap is a
 * tree walk. */
ATS_FN ats_vec3 ats_contact_gradient_at(ats_surface_distance s, ats_real k) {
  if (!(s.phi < 0)) return ats_v3(0, 0, 0);
  return ats_scale(s.n, k * s.phi);
}
ATS_FN ats_mat3 ats_contact_hessian_at(ats_surface_distance s, ats_real k) {
  ats_mat3 h = ats_m3_diag(0);
  if (!(s.phi < 0)) return h;
  h.r[0] = ats_scale(s.n, k * s.n.x);
  h.r[1] = ats_scale(s.n, k * s.n.y);
  h.r[2] = ats_scale(s.n, k * s.n.z);
  return h;
}
ATS_FN ats_vec3 ats_contact_gradient(ATS_GLOBAL const ats_collider_c* c, ats_vec3 x, ats_real mass, ats_real inv_h2) {
  return ats_contact_gradient_at(ats_collider_gap(c, x), c->stiffness * mass * inv_h2);
}
ATS_FN ats_mat3 ats_contact_hessian(ATS_GLOBAL const ats_collider_c* c, ats_vec3 x, ats_real mass, ats_real inv_h2) {
  return ats_contact_hessian_at(ats_collider_gap(c, x), c->stiffness * mass * inv_h2);
}

#endif
