/* The fused executor's dispatcher (DESIGN.md "Devices", fused): one launch
 * per device runs `substeps` substeps of that device's slots in schedule
 * order. Before a slot it waits for the completion counters the schedule
 * names (acquire); it runs the slot's launches with all its work-groups, each
 * taking one contiguous share of the range; every work-group then counts the
 * launch done on the task's counter (release). A wait also watches the
 * host's abort flag, so a device that never answers ends the launch instead
 * of hanging it. Launched with one work-item per work-group: a spinning
 * work-item must not share a work-group with one it waits for.
 * Appended to every program with task functions, after the generated
 * ats_run_range(function, args, begin, end). Needs OpenCL C 2.0 atomics. */
#include "device/dispatch_types.h"

#ifndef ATS_TASK_CLOCK
#define ATS_TASK_CLOCK 0
#endif

static inline ulong ats_clock(void) {
#if ATS_TASK_CLOCK
  return __builtin_readcyclecounter();
#else
  return 0;
#endif
}

static inline int ats_reached(__global int* counters, int task, int target) {
  __global atomic_int* c = (__global atomic_int*)(counters + ATS_LINE * task);
  return atomic_load_explicit(c, memory_order_acquire, memory_scope_device) >= target;
}

/* 1 when task's counter reached target, 0 when the host aborted first. */
static inline int ats_wait_for(__global int* counters, int task, int target, __global int* control) {
  __global atomic_int* abort_flag = (__global atomic_int*)control;
  while (!ats_reached(counters, task, target)) {
    if (atomic_load_explicit(abort_flag, memory_order_relaxed, memory_scope_device) != 0) return 0;
  }
  return 1;
}

static inline void ats_give_up(__global int* mine, int task, int waited_for) {
  if (atomic_exchange_explicit((__global atomic_int*)(mine + 1), 1, memory_order_relaxed, memory_scope_device) == 0) {
    mine[2] = task;
    mine[3] = waited_for;
  }
}

__kernel void ats_dispatch(__global const ats_slot* slots, int slot_count, __global const ats_launch* launches,
                           __global const ats_wait* waits, __global const ulong* args, __global int* counters,
                           __global int* control, __global ulong* stamps, int stamp_stride, int device, int epoch0,
                           int substeps, int record) {
  const int g = get_group_id(0);
  const int groups = get_num_groups(0);
  __global int* mine = control + ATS_LINE * (1 + device);
  for (int s = 0; s < substeps; ++s) {
    const int epoch = epoch0 + s;
    for (int k = 0; k < slot_count; ++k) {
      const ats_slot slot = slots[k];
      for (int w = 0; w < slot.wait_count; ++w) {
        const ats_wait wt = waits[slot.first_wait + w];
        if (!ats_wait_for(counters, wt.task, (epoch + wt.epoch_offset) * wt.units, control)) {
          ats_give_up(mine, slot.task, wt.task);
          return;
        }
      }
      const ulong start = ats_clock();
      ulong finish = start;
      __global atomic_int* done = (__global atomic_int*)(counters + ATS_LINE * slot.task);
      const int units = groups * slot.launch_count;
      for (int l = 0; l < slot.launch_count; ++l) {
        /* launches of one task run in order, as on an in-order queue */
        if (l > 0 && groups > 1 && !ats_wait_for(counters, slot.task, (epoch - 1) * units + l * groups, control)) {
          ats_give_up(mine, slot.task, slot.task);
          return;
        }
        const ats_launch run = launches[slot.first_launch + l];
        const int share = (run.count + groups - 1) / groups;
        const int begin = run.first + min(run.count, g * share);
        const int end = run.first + min(run.count, (g + 1) * share);
        if (begin < end) ats_run_range(run.function, args + run.first_arg, begin, end);
        /* stamped before the last publish: no consumer can start before it */
        if (l + 1 == slot.launch_count) finish = ats_clock();
        if (slot.publish) atomic_fetch_add_explicit(done, 1, memory_order_release, memory_scope_device);
      }
      if (record && s == substeps - 1) {
        stamps[2 * (stamp_stride * slot.task + g)] = start;
        stamps[2 * (stamp_stride * slot.task + g) + 1] = finish;
      }
      if (g == 0) {
        atomic_fetch_add_explicit((__global atomic_int*)mine, 1, memory_order_relaxed, memory_scope_device);
      }
    }
  }
}
