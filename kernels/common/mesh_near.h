/* A particle's near list of a mesh collider: the triangles within the
 * query's reach plus a margin of where the list was made, so that while the
 * particle stays within the margin its distance to the mesh is the nearest
 * of those few triangles instead of a walk of the mesh's tree, in the
 * common subset of C, C++ and OpenCL C.
 *
 * Why: a point inside a hollow mesh (a funnel) lies inside many of its
 * tree's boxes, far from their triangles, and its walk visits them all;
 * the clamps and projections of every iteration took two such walks per
 * particle (75 % of the paper funnel's substep at frame 6).
 *
 * Exact: any triangle nearer than the reach to x is nearer than the reach
 * plus |x - x0| to x0, so within the margin the list holds every triangle
 * the walk can find, and ats_mesh_consider picks the same one from either
 * (nearest, then lowest index). A list is made or kept once per substep
 * (colliders_near, common/contact_steps.cl) and its users check the
 * margin, so a stale or missing list only costs a walk: the results do not
 * depend on when lists were made (resume, profiling and repeats stay bit
 * for bit without carrying them). Made in the mesh's local frame, a list
 * stays valid when a kinematic mesh moves. */
#ifndef ATS_MESH_NEAR_H
#define ATS_MESH_NEAR_H

#include "common/mesh_contact.h"

#define ATS_MESH_NEAR_CAPACITY 11

/* 64 bytes. margin <= 0: no list; count > ATS_MESH_NEAR_CAPACITY: more
 * triangles were near than it holds (its users walk the tree). */
typedef struct {
  float x0[3];  /* where it was made, in the mesh's local frame */
  float margin; /* how far from x0 it serves */
  int count;
  int tri[ATS_MESH_NEAR_CAPACITY];
} ats_mesh_near;

/* The margin, in thicknesses of the collider: wider lists serve longer but
 * hold more triangles. */
#define ATS_MESH_NEAR_MARGIN 3.0f

/* Whether the list r serves the local point x: within 99 % of its margin
 * of x0 (the other 1 % is far above the rounding of the distances). */
ATS_FN int ats_mesh_near_serves(ATS_GLOBAL const ats_mesh_near* r, ats_vec3 x) {
  if (!(r->margin > 0) || r->count > ATS_MESH_NEAR_CAPACITY) return 0;
  const ats_vec3 d = ats_sub(x, ats_v3(r->x0[0], r->x0[1], r->x0[2]));
  const ats_real lim = (ats_real)0.99f * r->margin;
  return ats_dot(d, d) < lim * lim;
}

/* The list of the local point x for a query of `reach`: every triangle
 * nearer than reach + margin, by a walk pruned at that distance. */
ATS_FN_NOINLINE void ats_mesh_near_make(ATS_GLOBAL const ats_collider_c* c, ats_vec3 x, ats_real reach,
                                        ATS_GLOBAL ats_mesh_near* r) {
  ATS_GLOBAL const ats_bvh_node* nodes = ats_mesh_nodes(c);
  ATS_GLOBAL const ats_mesh_triangle* tris = ats_mesh_triangles(c);
  const ats_real margin = ATS_MESH_NEAR_MARGIN * c->thickness;
  const ats_real far2 = (reach + margin) * (reach + margin);
  int count = 0;
  int stack[ATS_BVH_STACK];
  int top = 0;
  stack[top++] = 0;
  while (top > 0 && count <= ATS_MESH_NEAR_CAPACITY) {
    ATS_GLOBAL const ats_bvh_node* node = nodes + stack[--top];
    if (ats_bvh_box_distance2(node, x) > ATS_MESH_PRUNE * far2) continue;
    if (node->count > 0) {
      for (int t = node->first; t < node->first + node->count && count <= ATS_MESH_NEAR_CAPACITY; ++t) {
        ats_mesh_hit h = ats_mesh_no_hit(x, reach + margin);
        ats_mesh_consider(tris, t, x, &h);
        if (h.t < 0) continue;
        if (count < ATS_MESH_NEAR_CAPACITY) r->tri[count] = t;
        ++count;
      }
    } else if (top + 2 <= ATS_BVH_STACK) {
      stack[top++] = node->first;
      stack[top++] = node->first + 1;
    } else {
      count = ATS_MESH_NEAR_CAPACITY + 1; /* too deep to see all: the users walk */
    }
  }
  r->x0[0] = x.x;
  r->x0[1] = x.y;
  r->x0[2] = x.z;
  r->margin = margin;
  r->count = count;
}

/* Keeps the list r while the local point x is within half its margin of
 * x0 (it then serves the substep's iterations), else makes it at x. */
ATS_FN void ats_mesh_near_refresh(ATS_GLOBAL const ats_collider_c* c, ats_vec3 x, ATS_GLOBAL ats_mesh_near* r) {
  if (r->margin > 0) {
    const ats_vec3 d = ats_sub(x, ats_v3(r->x0[0], r->x0[1], r->x0[2]));
    const ats_real keep = (ats_real)0.5f * r->margin;
    if (ats_dot(d, d) < keep * keep) return;
  }
  ats_mesh_near_make(c, x, c->mesh[3], r);
}

/* ats_mesh_distance, from the list r where it serves (r may be null). */
ATS_FN ats_surface_distance ats_mesh_distance_near(ATS_GLOBAL const ats_collider_c* c, ats_vec3 xw, ats_real reach,
                                                   ATS_GLOBAL const ats_mesh_near* r) {
  const ats_vec3 x = ats_mesh_local(c, xw);
  if (r == 0 || !ats_mesh_near_serves(r, x)) return ats_mesh_result(c, x, ats_mesh_walk(c, x, reach), reach);
  ATS_GLOBAL const ats_mesh_triangle* tris = ats_mesh_triangles(c);
  ats_mesh_hit h = ats_mesh_no_hit(x, reach);
  for (int k = 0; k < r->count; ++k) ats_mesh_consider(tris, r->tri[k], x, &h);
  return ats_mesh_result(c, x, h, reach);
}

#endif
