/* Device layouts of the element sets every method reads, shared by kernels
 * and host. */
#ifndef ATS_ELEMENT_TYPES_H
#define ATS_ELEMENT_TYPES_H

/* Distance (stretch) constraint, a spring of stiffness 1/compliance: 20
 * bytes. damping = Rayleigh stiffness-proportional beta in seconds: the
 * spring's damping coefficient along itself is c = beta / compliance (N s/m),
 * force c ((v_b - v_a) . n) n on a (common/energy_spring_damping.h); 0 = undamped. */
typedef struct {
  int a, b;
  float rest;
  float compliance;
  float damping;
} ats_distance_c;

/* Bending stencil: edge v[0]-v[1], opposite vertices v[2], v[3] (wings of
 * triangles (v0, v1, v2) and (v0, v3, v1)). Two models
 * (common/energy_bend_element.h):
 *   ATS_BEND_ISOMETRIC (Bergou et al. 2006, flat rest shape only):
 *     energy 0.5/compliance * scale * |sum K_i x_i|^2;
 *   ATS_BEND_DIHEDRAL (curved rest shapes): energy
 *     scale/compliance * (theta - rest_angle)^2 (common/energy_dihedral.h),
 *     scale = 3/2 |e|^2 / (A0 + A1) of the rest stencil, which equals the
 *     isometric energy to second order for a small fold of a flat stencil;
 *     K is unused (0).
 * 48 bytes. */
typedef struct {
  int v[4];
  float K[4];
  float scale;
  float compliance;
  float rest_angle; /* dihedral: theta_0, radians; isometric: 0 */
  int model;        /* ATS_BEND_ISOMETRIC or ATS_BEND_DIHEDRAL */
} ats_bend_c;

#define ATS_BEND_ISOMETRIC 0
#define ATS_BEND_DIHEDRAL 1

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
