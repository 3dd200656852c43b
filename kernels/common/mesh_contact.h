/* Distance of a point to a triangle-mesh obstacle (common/mesh_types.h),
 * in the common subset of C, C++ and OpenCL C (ats_real: float in kernels,
 * double in the Newton reference).
 *
 * Broad phase: the BVH over the mesh's triangles, walked with a small stack
 * and pruned by the nearest distance found so far (starting at the reach);
 * narrow phase: the closest point of a triangle (Ericson, Real-Time
 * Collision Detection §5.1.5), which also says which feature (face, edge,
 * vertex) it lies on.
 *
 * Inside and outside: a closed mesh (every edge shared by two consistently
 * oriented triangles) has a signed distance, negative inside, its sign from
 * the pseudo-normal of the nearest feature (Baerentzen & Aanaes 2005), so a
 * particle that went through the surface is pushed back out. An open mesh
 * (a funnel, a sheet) has no inside: its distance is unsigned, and a
 * particle is kept `thickness` away from either side. A point farther than
 * the reach from every triangle sees no contact, inside or not. */
#ifndef ATS_MESH_CONTACT_H
#define ATS_MESH_CONTACT_H

#include "common/ats_math.h"
#include "common/collider_types.h"
#include "common/surface_distance.h"

#define ATS_BVH_STACK 64

/* Feature of the closest point: 0 face, 1..3 vertex a, b, c, 4..6 edge ab, bc, ca. */
ATS_FN ats_vec3 ats_closest_on_triangle(ats_vec3 p, ats_vec3 a, ats_vec3 b, ats_vec3 c, int* feature) {
  const ats_vec3 ab = ats_sub(b, a), ac = ats_sub(c, a), ap = ats_sub(p, a);
  const ats_real d1 = ats_dot(ab, ap), d2 = ats_dot(ac, ap);
  if (d1 <= 0 && d2 <= 0) {
    *feature = 1;
    return a;
  }
  const ats_vec3 bp = ats_sub(p, b);
  const ats_real d3 = ats_dot(ab, bp), d4 = ats_dot(ac, bp);
  if (d3 >= 0 && d4 <= d3) {
    *feature = 2;
    return b;
  }
  const ats_real vc = d1 * d4 - d3 * d2;
  if (vc <= 0 && d1 >= 0 && d3 <= 0) {
    *feature = 4;
    return ats_add(a, ats_scale(ab, d1 / (d1 - d3)));
  }
  const ats_vec3 cp = ats_sub(p, c);
  const ats_real d5 = ats_dot(ab, cp), d6 = ats_dot(ac, cp);
  if (d6 >= 0 && d5 <= d6) {
    *feature = 3;
    return c;
  }
  const ats_real vb = d5 * d2 - d1 * d6;
  if (vb <= 0 && d2 >= 0 && d6 <= 0) {
    *feature = 6;
    return ats_add(a, ats_scale(ac, d2 / (d2 - d6)));
  }
  const ats_real va = d3 * d6 - d5 * d4;
  if (va <= 0 && (d4 - d3) >= 0 && (d5 - d6) >= 0) {
    *feature = 5;
    return ats_add(b, ats_scale(ats_sub(c, b), (d4 - d3) / ((d4 - d3) + (d5 - d6))));
  }
  *feature = 0;
  const ats_real denom = (ats_real)1 / (va + vb + vc);
  return ats_add(a, ats_add(ats_scale(ab, vb * denom), ats_scale(ac, vc * denom)));
}

ATS_FN ats_vec3 ats_mesh_float3(ATS_GLOBAL const float* v) { return ats_v3(v[0], v[1], v[2]); }

/* Squared distance of p to a node's box (0 inside it). */
ATS_FN ats_real ats_bvh_box_distance2(ATS_GLOBAL const ats_bvh_node* node, ats_vec3 p) {
  const ats_real q[3] = {p.x, p.y, p.z};
  ats_real d2 = 0;
  ATS_UNROLL for (int k = 0; k < 3; ++k) {
    const ats_real below = (ats_real)node->lo[k] - q[k];
    const ats_real above = q[k] - (ats_real)node->hi[k];
    const ats_real d = below > 0 ? below : (above > 0 ? above : (ats_real)0);
    d2 += d * d;
  }
  return d2;
}

/* The pseudo-normal of a triangle's feature (see ats_closest_on_triangle). */
ATS_FN ats_vec3 ats_feature_normal(ATS_GLOBAL const ats_mesh_triangle* t, int feature) {
  if (feature == 0) return ats_mesh_float3(t->n);
  if (feature <= 3) return ats_mesh_float3(t->vertex + 3 * (feature - 1));
  return ats_mesh_float3(t->edge + 3 * (feature - 4));
}

/* The nearest triangle a mesh query has found: its squared distance, index
 * (-1: none nearer than the reach), feature and closest point. */
typedef struct {
  ats_real d2;
  int t;
  int feature;
  ats_vec3 point;
} ats_mesh_hit;

ATS_FN_INLINE ats_mesh_hit ats_mesh_no_hit(ats_vec3 x, ats_real reach) {
  ats_mesh_hit h;
  h.d2 = reach * reach;
  h.t = -1;
  h.feature = 0;
  h.point = x;
  return h;
}

/* Triangle t of the local point x against the hit so far. The nearer wins
 * and an equal distance goes to the lower index, so that the tree walk
 * and a near list (common/mesh_near.h), which meet the same triangles in
 * other orders, find the same one, bit for bit. */
ATS_FN_INLINE void ats_mesh_consider(ATS_GLOBAL const ats_mesh_triangle* tris, int t, ats_vec3 x, ats_mesh_hit* h) {
  int feature = 0;
  const ats_vec3 q = ats_closest_on_triangle(x, ats_mesh_float3(tris[t].p), ats_mesh_float3(tris[t].p + 3),
                                             ats_mesh_float3(tris[t].p + 6), &feature);
  const ats_vec3 e = ats_sub(x, q);
  const ats_real d2 = ats_dot(e, e);
  if (d2 < h->d2 || (d2 == h->d2 && h->t >= 0 && t < h->t)) {
    h->d2 = d2;
    h->t = t;
    h->feature = feature;
    h->point = q;
  }
}

/* A node is passed over when its box is farther than the nearest triangle
 * by more than this factor on the squared distance: a box holds its
 * triangles, but both distances are rounded, and a triangle at the nearest
 * distance (a tie) must still be met. */
#define ATS_MESH_PRUNE ((ats_real)1.001)

ATS_FN ATS_GLOBAL const ats_bvh_node* ats_mesh_nodes(ATS_GLOBAL const ats_collider_c* c) {
  return (ATS_GLOBAL const ats_bvh_node*)(c + (int)c->mesh[0]);
}
ATS_FN ATS_GLOBAL const ats_mesh_triangle* ats_mesh_triangles(ATS_GLOBAL const ats_collider_c* c) {
  return (ATS_GLOBAL const ats_mesh_triangle*)(c + (int)c->mesh[1]);
}

/* The world point xw in the mesh's local frame. */
ATS_FN ats_vec3 ats_mesh_local(ATS_GLOBAL const ats_collider_c* c, ats_vec3 xw) {
  const ats_vec3 d = ats_sub(xw, ats_mesh_float3(c->c));
  return ats_v3(ats_dot(d, ats_mesh_float3(c->axes)), ats_dot(d, ats_mesh_float3(c->axes + 4)),
                ats_dot(d, ats_mesh_float3(c->axes + 8)));
}

/* The nearest triangle to the local point x nearer than `reach`, by a walk
 * of the tree with a small stack, pruned by the nearest distance so far. */
ATS_FN_NOINLINE ats_mesh_hit ats_mesh_walk(ATS_GLOBAL const ats_collider_c* c, ats_vec3 x, ats_real reach) {
  ATS_GLOBAL const ats_bvh_node* nodes = ats_mesh_nodes(c);
  ATS_GLOBAL const ats_mesh_triangle* tris = ats_mesh_triangles(c);
  ats_mesh_hit h = ats_mesh_no_hit(x, reach);
  int stack[ATS_BVH_STACK];
  int top = 0;
  stack[top++] = 0;
  while (top > 0) {
    ATS_GLOBAL const ats_bvh_node* node = nodes + stack[--top];
    if (ats_bvh_box_distance2(node, x) > ATS_MESH_PRUNE * h.d2) continue;
    if (node->count > 0) {
      for (int t = node->first; t < node->first + node->count; ++t) ats_mesh_consider(tris, t, x, &h);
    } else if (top + 2 <= ATS_BVH_STACK) {
      /* the nearer child last, so that it is walked first and prunes more */
      const ats_real d0 = ats_bvh_box_distance2(nodes + node->first, x);
      const ats_real d1 = ats_bvh_box_distance2(nodes + node->first + 1, x);
      stack[top++] = d0 < d1 ? node->first + 1 : node->first;
      stack[top++] = d0 < d1 ? node->first : node->first + 1;
    }
  }
  return h;
}

/* The distance and world normal of the local point x from its hit h. */
ATS_FN ats_surface_distance ats_mesh_result(ATS_GLOBAL const ats_collider_c* c, ats_vec3 x, ats_mesh_hit h,
                                            ats_real reach) {
  ats_surface_distance s;
  if (h.t < 0) {
    s.phi = reach;
    s.n = ats_v3(0, 1, 0);
    return s;
  }
  ATS_GLOBAL const ats_mesh_triangle* tris = ats_mesh_triangles(c);
  const ats_real dist = ATS_SQRT(h.d2);
  const ats_vec3 e = ats_sub(x, h.point);
  ats_vec3 n;
  if (c->mesh[2] > 0.5f) { /* closed: signed by the pseudo-normal */
    const ats_vec3 pn = ats_feature_normal(tris + h.t, h.feature);
    const ats_real sign = ats_dot(e, pn) < 0 ? (ats_real)-1 : (ats_real)1;
    s.phi = sign * dist;
    n = dist > (ats_real)1e-12 ? ats_scale(e, sign / dist) : pn;
  } else { /* open: unsigned, away from the nearest point */
    s.phi = dist;
    n = dist > (ats_real)1e-12 ? ats_scale(e, (ats_real)1 / dist) : ats_mesh_float3(tris[h.t].n);
  }
  s.n = ats_add(ats_add(ats_scale(ats_mesh_float3(c->axes), n.x), ats_scale(ats_mesh_float3(c->axes + 4), n.y)),
                ats_scale(ats_mesh_float3(c->axes + 8), n.z));
  return s;
}

/* Distance to the mesh of collider c from the world point xw, within
 * `reach` (no triangle nearer: phi = reach, normal up). */
ATS_FN ats_surface_distance ats_mesh_distance(ATS_GLOBAL const ats_collider_c* c, ats_vec3 xw, ats_real reach) {
  const ats_vec3 x = ats_mesh_local(c, xw);
  return ats_mesh_result(c, x, ats_mesh_walk(c, x, reach), reach);
}

#endif
