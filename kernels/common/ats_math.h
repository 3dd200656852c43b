/* Small vector math in the common subset of C, C++ and OpenCL C, so the
 * element math below compiles both in kernels and in host code (DESIGN.md:
 * one truth for the math).
 *
 * The scalar type is the macro ats_real, float unless the including file
 * defines it first: kernels and the float host twins use float; host code
 * that needs double (the Newton reference) defines ats_real as double before
 * the first include (see lib/solver/energy/element_math.hpp). */
#ifndef ATS_MATH_H
#define ATS_MATH_H

#ifndef ats_real
#define ats_real float
#endif

#ifdef __OPENCL_VERSION__
#define ATS_FN static inline
#define ATS_UNROLL _Pragma("unroll")
#define ATS_SQRT(x) sqrt(x)
#define ATS_FMA(a, b, c) fma(a, b, c)
#elif defined(__cplusplus)
#include <math.h> /* C++ <math.h>: sqrt and fma are overloaded for float and double */
#define ATS_FN static inline
#define ATS_UNROLL
#define ATS_SQRT(x) sqrt(x)
#define ATS_FMA(a, b, c) fma(a, b, c)
#else
#include <tgmath.h> /* C: type-generic sqrt and fma */
#define ATS_FN static inline
#define ATS_UNROLL
#define ATS_SQRT(x) sqrt(x)
#define ATS_FMA(a, b, c) fma(a, b, c)
#endif

/* ATS_FN_INLINE: a small function the compiler must inline into its caller
 * even where it judges the caller too large (pocl had left the collider
 * distances out of line, one call per particle and collider);
 * ATS_FN_NOINLINE: a large, rarely taken branch kept out of such a caller
 * (a mesh collider's tree walk). */
#if defined(__OPENCL_VERSION__) || defined(__GNUC__)
#define ATS_FN_INLINE static inline __attribute__((always_inline, unused))
#define ATS_FN_NOINLINE static __attribute__((noinline, unused))
#else
#define ATS_FN_INLINE static inline
#define ATS_FN_NOINLINE static
#endif

/* The address space of the arrays a kernel is handed; host code has only
 * one. Lets a function over particle and element arrays compile both ways. */
#ifdef __OPENCL_VERSION__
#define ATS_GLOBAL __global
#else
#define ATS_GLOBAL
#endif

/* A particle, four floats x, y, z, w (w = inverse mass): OpenCL's float4 in
 * kernels; host code that shares such arrays defines ats_float4 first as its
 * own 16-byte struct with those fields (solver::Float4). */
#if defined(__OPENCL_VERSION__) && !defined(ats_float4)
#define ats_float4 float4
#endif

typedef struct {
  ats_real x, y, z;
} ats_vec3;

ATS_FN ats_vec3 ats_v3(ats_real x, ats_real y, ats_real z) {
  ats_vec3 r;
  r.x = x;
  r.y = y;
  r.z = z;
  return r;
}
ATS_FN ats_vec3 ats_add(ats_vec3 a, ats_vec3 b) { return ats_v3(a.x + b.x, a.y + b.y, a.z + b.z); }
ATS_FN ats_vec3 ats_sub(ats_vec3 a, ats_vec3 b) { return ats_v3(a.x - b.x, a.y - b.y, a.z - b.z); }
ATS_FN ats_vec3 ats_scale(ats_vec3 a, ats_real s) { return ats_v3(a.x * s, a.y * s, a.z * s); }
ATS_FN ats_real ats_dot(ats_vec3 a, ats_vec3 b) { return a.x * b.x + a.y * b.y + a.z * b.z; }
ATS_FN ats_real ats_length(ats_vec3 a) { return ATS_SQRT(ats_dot(a, a)); }

#endif
