/* Device layout of a triangle-mesh obstacle, shared by kernels and host:
 * its BVH nodes and triangles follow the collider records in the same
 * buffer (ats_collider_c.mesh says where, in records from the mesh's own
 * record), in the mesh's local frame. 4-byte fields only, so that the C++
 * and OpenCL C layouts agree. */
#ifndef ATS_MESH_TYPES_H
#define ATS_MESH_TYPES_H

/* A node of the obstacle's bounding volume hierarchy (32 bytes). A leaf
 * (count > 0) holds triangles first .. first + count - 1; an inner node
 * (count == 0) has its two children at first and first + 1. Node 0 is the
 * root. */
typedef struct {
  float lo[3];
  int first;
  float hi[3];
  int count;
} ats_bvh_node;

/* A triangle with the pseudo-normals that sign the distance of a closed
 * mesh (Baerentzen & Aanaes 2005): face, edges ab, bc, ca (sum of the two
 * faces' normals) and vertices a, b, c (angle-weighted), 128 bytes. */
typedef struct {
  float p[9];      /* a, b, c */
  float n[3];      /* unit face normal, (b - a) x (c - a) */
  float edge[9];   /* edge pseudo-normals ab, bc, ca (closed meshes) */
  float vertex[9]; /* vertex pseudo-normals a, b, c (closed meshes) */
  float pad[2];
} ats_mesh_triangle;

#endif
