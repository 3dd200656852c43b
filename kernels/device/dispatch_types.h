/* The records a fused dispatcher walks (device/dispatch.cl), in the common
 * subset of C, C++ and OpenCL C: the host (lib/device/fused_executor.cpp)
 * writes them into SVM, the device reads them. All ints, so the layouts
 * agree without packing rules. */
#ifndef ATS_DISPATCH_TYPES_H
#define ATS_DISPATCH_TYPES_H

/* One task of this device's schedule, in slot order. */
typedef struct {
  int task;         /* task id: its completion counter */
  int first_launch; /* into the launch records */
  int launch_count; /* ≥ 1 (a task without work gets one empty launch) */
  int first_wait;   /* into the wait records */
  int wait_count;
  int publish; /* 0 only for the test that a wait never completes */
  int pad0, pad1;
} ats_slot;

/* One task function over elements [first, first + count). */
typedef struct {
  int function; /* case of the program's ats_run_range */
  int first;
  int count;
  int first_arg; /* into the argument words (64 bits each) */
} ats_launch;

/* Wait until task's counter reaches (epoch + epoch_offset) * units: every
 * work-group of its device has finished each of its launches `units` times
 * counted per substep. */
typedef struct {
  int task;
  int units;
  int epoch_offset; /* 0: this substep; -1: the one before */
  int pad;
} ats_wait;

/* Ints per counter (and per control record): 64 bytes, one cache line, so
 * that devices do not share a line they both write. */
#define ATS_LINE 16

/* Control block: [0] the host's abort flag; then per device d one line at
 * ATS_LINE * (1 + d): [0] slots finished (progress), [1] 1 once it gave up
 * waiting, [2] the task it was to run, [3] the task it waited for. */
#define ATS_CONTROL_INTS(devices) (ATS_LINE * (1 + (devices)))

#endif
