/* Probes the device layer runs before trusting a set of devices. Needs
 * OpenCL C 2.0 atomics in fine-grain SVM. Every spin also watches the abort
 * flag in control[0], which the host sets when a probe takes too long. */

/* Two of these, one per device (role 0 and 1), pass a counter back and
 * forth `hops` times: the fused executor's cross-device hop, and the proof
 * that the two devices really run at the same time. */
__kernel void probe_handshake(__global int* flag, int role, int hops, __global int* control) {
  __global atomic_int* f = (__global atomic_int*)flag;
  __global atomic_int* abort_flag = (__global atomic_int*)control;
  for (int h = 0; h < hops; ++h) {
    const int mine = 2 * h + role;
    while (atomic_load_explicit(f, memory_order_acquire, memory_scope_device) != mine) {
      if (atomic_load_explicit(abort_flag, memory_order_relaxed, memory_scope_device) != 0) return;
    }
    atomic_store_explicit(f, mine + 1, memory_order_release, memory_scope_device);
  }
}

/* Every work-group (one work-item each) arrives, then waits for all:
 * whether a device runs all its work-groups at once, as the dispatcher's
 * device-wide barrier needs. */
__kernel void probe_gather(__global int* counter, __global int* control) {
  __global atomic_int* c = (__global atomic_int*)counter;
  __global atomic_int* abort_flag = (__global atomic_int*)control;
  atomic_fetch_add_explicit(c, 1, memory_order_acq_rel, memory_scope_device);
  while (atomic_load_explicit(c, memory_order_acquire, memory_scope_device) < (int)get_num_groups(0)) {
    if (atomic_load_explicit(abort_flag, memory_order_relaxed, memory_scope_device) != 0) return;
  }
}
