/* Device layouts of the element sets every method reads, shared by kernels
 * and host. */
#ifndef ATS_ELEMENT_TYPES_H
#define ATS_ELEMENT_TYPES_H

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

/* A linear tetrahedron (Sifakis & Barbic 2012): vertices, rest-shape
 * inverse Dm^-1 (row-major), rest volume, Lame parameters, energy model
 * (0 stable neo-Hookean, 1 StVK; kernels/common/energy_tet_*.h). 64 bytes. */
typedef struct {
  int v[4];
  float dm_inv[9];
  float volume;
  float mu;
  float lambda;
  int model;
} ats_tet_c;

#define ATS_TET_NEO_HOOKEAN 0
#define ATS_TET_STVK 1

#endif
