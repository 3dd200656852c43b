/* Device layout of an analytic collider (plane, sphere, capsule, box),
 * shared by kernels and host. Floats only, so that the C++ and OpenCL C
 * layouts agree without alignment rules: 32 floats, 128 bytes. */
#ifndef ATS_COLLIDER_TYPES_H
#define ATS_COLLIDER_TYPES_H

#define ATS_COLLIDER_PLANE 0
#define ATS_COLLIDER_SPHERE 1
#define ATS_COLLIDER_CAPSULE 2
#define ATS_COLLIDER_BOX 3

typedef struct {
  float shape;     /* ATS_COLLIDER_* (a float: the struct holds floats only) */
  float thickness; /* contact offset from the surface, metres (> 0) */
  float mu_s;      /* Coulomb static friction coefficient (>= 0) */
  float mu_k;      /* Coulomb kinetic friction coefficient (>= 0) */
  float c[4];      /* plane: a point on it; sphere, box: centre; capsule: end a */
  float n[4];      /* plane: unit normal; capsule: end b */
  float axes[12];  /* box: its local x, y, z axes in world coordinates (rows of 4) */
  float extent[4]; /* box: half extents along its axes ("half" is an OpenCL C type) */
  float radius;    /* sphere, capsule */
  float stiffness; /* contact energy stiffness relative to m/h^2 (dimensionless, > 0) */
  float pad0, pad1;
} ats_collider_c;

#endif
