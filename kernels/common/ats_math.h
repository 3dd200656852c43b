/* Small vector math in the common subset of C, C++ and OpenCL C, so the
 * element math below compiles both in kernels and in host code (DESIGN.md:
 * one truth for the math). */
#ifndef ATS_MATH_H
#define ATS_MATH_H

#ifdef __OPENCL_VERSION__
#define ATS_FN static inline
#define ATS_SQRT(x) sqrt(x)
#else
#include <math.h>
#define ATS_FN static inline
#define ATS_SQRT(x) sqrtf(x)
#endif

typedef struct {
  float x, y, z;
} ats_vec3;

ATS_FN ats_vec3 ats_v3(float x, float y, float z) {
  ats_vec3 r;
  r.x = x;
  r.y = y;
  r.z = z;
  return r;
}
ATS_FN ats_vec3 ats_add(ats_vec3 a, ats_vec3 b) { return ats_v3(a.x + b.x, a.y + b.y, a.z + b.z); }
ATS_FN ats_vec3 ats_sub(ats_vec3 a, ats_vec3 b) { return ats_v3(a.x - b.x, a.y - b.y, a.z - b.z); }
ATS_FN ats_vec3 ats_scale(ats_vec3 a, float s) { return ats_v3(a.x * s, a.y * s, a.z * s); }
ATS_FN float ats_dot(ats_vec3 a, ats_vec3 b) { return a.x * b.x + a.y * b.y + a.z * b.z; }
ATS_FN float ats_length(ats_vec3 a) { return ATS_SQRT(ats_dot(a, a)); }

#endif
