/* A signed distance to a surface with its gradient, what every collider's
 * distance function returns (common/collider_distance.h, mesh_contact.h). */
#ifndef ATS_SURFACE_DISTANCE_H
#define ATS_SURFACE_DISTANCE_H

#include "common/ats_math.h"

typedef struct {
  ats_real phi; /* signed distance to the surface (negative inside) */
  ats_vec3 n;   /* unit outward normal: the gradient of phi */
} ats_surface_distance;

#endif
