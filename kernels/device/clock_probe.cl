/* Whether the device's compiler offers a cycle counter (clang's
 * __builtin_readcyclecounter: pocl's CPU devices), and its reading: the
 * fused dispatcher stamps each task with it. A separate program, because a
 * compiler without it fails to build this one only. */
__kernel void probe_clock(__global ulong* out) { out[0] = __builtin_readcyclecounter(); }
