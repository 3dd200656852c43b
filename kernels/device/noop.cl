/* An empty kernel: the events executor times event hops with it. Its own
 * program, in OpenCL C 1.2, so a device without OpenCL C 2.0 atomics (which
 * the fused executor's probes in probe.cl need) builds it. */
__kernel void probe_noop(__global int* unused) { (void)unused; }
