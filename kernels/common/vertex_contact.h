/* The contact energy (common/collider_distance.h) in a vertex's force and
 * Hessian block, for the vertex-block methods (VBD, JPGD, SOSD) and the
 * host VBD reference: every collider's penalty term of the particle. */
#ifndef ATS_VERTEX_CONTACT_H
#define ATS_VERTEX_CONTACT_H

#include "common/collider_distance.h"
#include "common/vertex_system.h"

ATS_FN vertex_system add_contact_terms(vertex_system s, ats_vec3 xi, float inv_mass, float inv_h2,
                                       ATS_GLOBAL const ats_collider_c* colliders, int count,
                                       ATS_GLOBAL const ats_mesh_near* near) {
  if (inv_mass == 0.0f) return s;
  const float mass = 1.0f / inv_mass;
  for (int c = 0; c < count; ++c) {
    if (ats_collider_clear(colliders + c, xi)) continue; /* both terms are zero */
    const ats_surface_distance gap = ats_collider_gap_near(colliders + c, xi, near);
    const float k = colliders[c].stiffness * mass * inv_h2;
    s.f = ats_sub(s.f, ats_contact_gradient_at(gap, k));
    s.h = ats_m3_add(s.h, ats_contact_hessian_at(gap, k));
  }
  return s;
}

#endif
