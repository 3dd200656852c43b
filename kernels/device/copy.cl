/* Copies between memories (lib/device/memory_copies.cpp): the listed
 * elements of a buffer, gathered into a packed buffer on the device that
 * wrote them and scattered back on the device that needs them, so that a
 * copy carries exactly the elements written (two devices may write
 * interleaved elements of one buffer). An element is `words` 32-bit words;
 * one work-item per element. */
__kernel void ats_gather(__global uint* packed, __global const uint* src, __global const int* idx, int words,
                         int count) {
  const int k = get_global_id(0);
  if (k >= count) return;
  const int e = idx[k];
  for (int w = 0; w < words; ++w) packed[k * words + w] = src[e * words + w];
}

__kernel void ats_scatter(__global uint* dst, __global const uint* packed, __global const int* idx, int words,
                          int count) {
  const int k = get_global_id(0);
  if (k >= count) return;
  const int e = idx[k];
  for (int w = 0; w < words; ++w) dst[e * words + w] = packed[k * words + w];
}
