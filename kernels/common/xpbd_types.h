/* Device layouts of the XPBD element sets, shared by kernels and host. */
#ifndef ATS_XPBD_TYPES_H
#define ATS_XPBD_TYPES_H

/* Distance (stretch) constraint: 16 bytes. */
typedef struct {
  int a, b;
  float rest;
  float compliance;
} ats_distance_c;

/* Isometric bending stencil (Bergou et al. 2006): edge v[0]-v[1], opposite
 * vertices v[2], v[3]; energy 0.5/compliance * scale * |sum K_i x_i|^2.
 * 48 bytes. */
typedef struct {
  int v[4];
  float K[4];
  float scale;
  float compliance;
  float pad0, pad1;
} ats_bend_c;

#endif
