/* Friction of the vertex-block methods (VBD, JPGD, SOSD): as
 * particles_friction (common/contact_steps.cl), with the normal
 * displacement taken from the force the contact must balance at the
 * result, inertia and elasticity together: dn = (h^2 / m) max(0, -n . f),
 * f the vertex force of the incremental potential without the contact
 * energy (common/vertex_system.h). Inertia alone (particles_friction) misses
 * the cloth's tension pressing it onto a curved collider. Reads x, writes
 * x_out (every particle), so no vertex sees another's friction step. */
ATS_TASK void vertex_friction(int i, __global const float4* x, __global float4* x_out, __global const float4* x_prev,
                              __global const float4* x_tilde, __global const int* adj_offsets, __global const int* adj,
                              __global const ats_distance_c* stretch, __global const ats_bend_c* bend,
                              __global const ats_tet_c* tets, __global const ats_collider_c* colliders, int count,
                              __global const ats_mesh_near* near, float inv_h2, __global const float2* pf) {
  const float4 p = x[i];
  x_out[i] = p;
  if (p.w == 0.0f) return;
  ats_vec3 n;
  __global const ats_mesh_near* mine = ats_near_of(colliders, count, near, i);
  const int c = touching_collider(p, colliders, count, mine, &n);
  if (c < 0) return;
  const vertex_system s = gather_vertex_system(i, x, x_tilde, inv_h2, adj_offsets, adj, stretch, bend, tets);
  const float dn = -ats_dot(s.f, n) * p.w / inv_h2;
  x_out[i] = no_deeper(coulomb_friction(p, x_prev[i], n, dn, colliders + c, contact_mu(colliders + c, pf[i])), p,
                       colliders + c, mine);
}
