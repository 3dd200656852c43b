/* Contact with analytic colliders (kernels/common/collider_distance.h),
 * the tasks every method runs when its scene has colliders:
 *   particles_contact: at the end of every iteration (XPBD, JPGD), a
 *     particle inside a collider's thickened surface is put back on it
 *     (XPBD's inequality constraint with zero compliance);
 *   particles_friction: once per substep, after the iterations, Coulomb
 *     friction on the substep's displacement (position-based friction,
 *     Macklin et al. 2014 §6): the normal displacement the contact caused
 *     this substep, dn = n . (x - x~) with x~ = x_t + h v (v is still the
 *     predicted velocity), bounds the tangential one: it is removed whole
 *     while |u_t| <= mu_s dn (static), else shortened by mu_k dn (kinetic).
 * Both range over independent particles. */
#include "common/collider_distance.h"
#include "common/task.h"

/* Every particle's near lists of the mesh colliders (common/mesh_near.h),
 * kept or made at its position at the substep's start, before any task
 * that takes them. */
ATS_TASK void colliders_near(int i, __global const float4* x, __global const ats_collider_c* colliders, int count,
                             __global ats_mesh_near* near) {
  if (count == 0) return;
  const float4 p = x[i];
  __global ats_mesh_near* mine = near + i * (int)colliders[0].near_slots;
  for (int c = 0; c < count; ++c) {
    if ((int)colliders[c].shape != ATS_COLLIDER_MESH) continue;
    ats_mesh_near_refresh(colliders + c, ats_mesh_local(colliders + c, ats_v3(p.x, p.y, p.z)),
                          mine + (int)colliders[c].near_slot);
  }
}

ATS_TASK void particles_contact(int i, __global float4* x, __global const ats_collider_c* colliders, int count,
                                __global const ats_mesh_near* near) {
  float4 p = x[i];
  if (p.w == 0.0f) return;
  __global const ats_mesh_near* mine = ats_near_of(colliders, count, near, i);
  for (int c = 0; c < count; ++c) {
    if (ats_collider_clear(colliders + c, ats_v3(p.x, p.y, p.z))) continue;
    const ats_surface_distance s = ats_collider_gap_near(colliders + c, ats_v3(p.x, p.y, p.z), mine);
    if (s.phi < 0.0f) p = (float4)(p.x - s.phi * s.n.x, p.y - s.phi * s.n.y, p.z - s.phi * s.n.z, p.w);
  }
  x[i] = p;
}

/* The collider particle p touches with the smallest gap (-1: none), and its normal. */
static inline int touching_collider(float4 p, __global const ats_collider_c* colliders, int count,
                                    __global const ats_mesh_near* near, ats_vec3* normal) {
  int best = -1;
  float best_gap = 0.0f;
  for (int c = 0; c < count; ++c) {
    const ats_surface_distance s = ats_collider_gap_near(colliders + c, ats_v3(p.x, p.y, p.z), near);
    if (ats_collider_touching(colliders + c, s.phi) && (best < 0 || s.phi < best_gap)) {
      best = c;
      best_gap = s.phi;
      *normal = s.n;
    }
  }
  return best;
}

/* How far the collider's surface at p moved this substep (kinematic
 * colliders; zero for static ones): friction acts on the motion relative
 * to it. */
static inline ats_vec3 surface_motion(__global const ats_collider_c* c, float4 p) {
  const ats_vec3 r = ats_v3(p.x - c->pivot[0], p.y - c->pivot[1], p.z - c->pivot[2]);
  const ats_vec3 w = ats_v3(c->turn[0], c->turn[1], c->turn[2]);
  const ats_vec3 wxr = ats_v3(w.y * r.z - w.z * r.y, w.z * r.x - w.x * r.z, w.x * r.y - w.y * r.x);
  return ats_add(ats_v3(c->move[0], c->move[1], c->move[2]), wxr);
}

/* The coefficients (mu_s, mu_k) between collider c and a particle of a
 * material with pf (-1: unset; so is a collider's without `friction:`): the
 * mean when both are set, else the one that is, else none. */
static inline float2 contact_mu(__global const ats_collider_c* c, float2 pf) {
  const float2 cm = (float2)(c->mu_s, c->mu_k);
  if (cm.x < 0.0f) return pf.x < 0.0f ? (float2)(0.0f) : pf;
  return pf.x < 0.0f ? cm : 0.5f * (cm + pf);
}

/* Coulomb friction on the substep's displacement from q (x_t) to p relative
 * to the collider's surface, given the normal displacement dn the contact
 * caused (see above), with the coefficients mu = (mu_s, mu_k). */
static inline float4 coulomb_friction(float4 p, float4 q, ats_vec3 n, float dn, __global const ats_collider_c* c,
                                      float2 mu) {
  if (!(dn > 0.0f)) return p;
  const ats_vec3 u = ats_sub(ats_v3(p.x - q.x, p.y - q.y, p.z - q.z), surface_motion(c, p));
  const ats_vec3 ut = ats_sub(u, ats_scale(n, ats_dot(u, n)));
  const float len = ats_length(ut);
  if (!(len > 0.0f)) return p;
  const float keep = len <= mu.x * dn ? 0.0f : fmax(0.0f, 1.0f - mu.y * dn / len);
  const ats_vec3 removed = ats_scale(ut, 1.0f - keep);
  return (float4)(p.x - removed.x, p.y - removed.y, p.z - removed.z, p.w);
}

/* Friction moves a particle along the surface, which on a curved or faceted
 * collider can take it into the thickened surface: f, the step's result
 * from p, is put back to p's gap (or onto the surface, if p was outside).
 * Friction never deepens a contact (before: cloth on a mesh figure ended
 * 1.02 % of the thickness inside under VBD, 0 with friction off). */
static inline float4 no_deeper(float4 f, float4 p, __global const ats_collider_c* c,
                               __global const ats_mesh_near* near) {
  const float before = fmin(ats_collider_gap_near(c, ats_v3(p.x, p.y, p.z), near).phi, 0.0f);
  const ats_surface_distance s = ats_collider_gap_near(c, ats_v3(f.x, f.y, f.z), near);
  if (!(s.phi < before)) return f;
  const float push = before - s.phi;
  return (float4)(f.x + push * s.n.x, f.y + push * s.n.y, f.z + push * s.n.z, f.w);
}

ATS_TASK void particles_friction(int i, __global float4* x, __global const float4* x_prev, __global const float4* v,
                                 __global const ats_collider_c* colliders, int count,
                                 __global const ats_mesh_near* near, float dt, __global const float2* pf) {
  const float4 p = x[i];
  if (p.w == 0.0f) return;
  __global const ats_mesh_near* mine = ats_near_of(colliders, count, near, i);
  ats_vec3 n;
  const int c = touching_collider(p, colliders, count, mine, &n);
  if (c < 0) return;
  const float4 q = x_prev[i];
  const float4 vel = v[i];
  const ats_vec3 predicted = ats_v3(q.x + dt * vel.x, q.y + dt * vel.y, q.z + dt * vel.z);
  const float dn = ats_dot(ats_sub(ats_v3(p.x, p.y, p.z), predicted), n);
  x[i] =
      no_deeper(coulomb_friction(p, q, n, dn, colliders + c, contact_mu(colliders + c, pf[i])), p, colliders + c, mine);
}
