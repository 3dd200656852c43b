/* Device layout of a collider (plane, sphere, capsule, box, triangle mesh),
 * shared by kernels and host. Floats only, so that the C++ and OpenCL C
 * layouts agree without alignment rules: 48 floats, 192 bytes. A mesh's
 * BVH and triangles (common/mesh_types.h) follow the records in the same
 * buffer. */
#ifndef ATS_COLLIDER_TYPES_H
#define ATS_COLLIDER_TYPES_H

#define ATS_COLLIDER_PLANE 0
#define ATS_COLLIDER_SPHERE 1
#define ATS_COLLIDER_CAPSULE 2
#define ATS_COLLIDER_BOX 3
#define ATS_COLLIDER_MESH 4

#include "common/mesh_types.h"

typedef struct {
  float shape;     /* ATS_COLLIDER_* (a float: the struct holds floats only) */
  float thickness; /* contact offset from the surface, metres (> 0) */
  float mu_s;      /* Coulomb static friction coefficient (>= 0) */
  float mu_k;      /* Coulomb kinetic friction coefficient (>= 0) */
  float c[4];      /* plane: a point on it; sphere, box: centre; capsule: end a; mesh: position */
  float n[4];      /* plane: unit normal; capsule: end b */
  float axes[12];  /* box, mesh: local x, y, z axes in world coordinates (rows of 4) */
  float extent[4]; /* box: half extents along its axes ("half" is an OpenCL C type) */
  float radius;    /* sphere, capsule */
  float stiffness; /* contact energy stiffness relative to m/h^2 (dimensionless, > 0) */
  /* Near lists (common/mesh_near.h): a mesh's slot among a particle's
   * lists, and (in every record) how many lists a particle has: one per
   * mesh collider. Floats, like the rest. */
  float near_slot, near_slots;
  /* Kinematic colliders: the surface's motion over the current substep, so
   * that friction acts on the velocity relative to it: a surface point p
   * moved by move + turn x (p - pivot) (zero for a static collider). */
  float move[4];  /* displacement of the pivot over the substep, metres */
  float turn[4];  /* rotation vector of the substep (axis * angle, radians) */
  float pivot[4]; /* the pivot at the substep's end */
  /* mesh: records from this one to its first BVH node and first triangle,
   * 1 for a closed mesh (signed distance) or 0 for an open one (unsigned),
   * and the reach of the query (no triangle nearer: no contact). The box's
   * c and axes place the mesh's local frame. */
  float mesh[4];
} ats_collider_c;

#endif
