/* Data exchange of asynchronous Gauss-Seidel (He et al. 2025 §4.2.2).
 * Positions are float4 with w = inverse mass; w is never merged. Included by
 * every solver program that runs asynchronously. */
#include "common/task.h"

/* Snapshot of a device's positions for other devices to merge. */
ATS_TASK void async_publish(int i, __global float4* dst, __global const float4* src) { dst[i] = src[i]; }

#define ATS_MERGE_COPY 0
#define ATS_MERGE_AVERAGE_POSITIONS 1
#define ATS_MERGE_AVERAGE_DISPLACEMENTS 2

/* dst (this device's copy) <- merge(dst, other) from the explicit start
 * point `start` (the state both descend from):
 *   copy:                  other
 *   average positions:     (dst + other) / 2
 *   average displacements: start + the mean of the displacements of the
 *                          copies that moved the particle since `start` */
ATS_TASK void async_merge(int i, __global float4* dst, __global const float4* other, __global const float4* start,
                          int strategy) {
  const float4 a = dst[i];
  const float4 b = other[i];
  float3 r;
  if (strategy == ATS_MERGE_COPY) {
    r = b.xyz;
  } else if (strategy == ATS_MERGE_AVERAGE_POSITIONS) {
    r = 0.5f * (a.xyz + b.xyz);
  } else {
    const float3 s = start[i].xyz;
    const float3 da = a.xyz - s;
    const float3 db = b.xyz - s;
    const int moved_a = any(da != (float3)(0.0f));
    const int moved_b = any(db != (float3)(0.0f));
    r = (moved_a && moved_b) ? s + 0.5f * (da + db) : s + da + db;
  }
  dst[i] = (float4)(r, a.w);
}
