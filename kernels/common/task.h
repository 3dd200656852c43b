/* A task function: the body of one element of a plan's kernel launch,
 * declared as `ATS_TASK void name(int i, parameters…)` and followed by the
 * body that handles element i. Every such declaration in a program's source is turned at build time
 * (kernels/embed_kernels.cmake) into a thin kernel for the events executor,
 * ats_k_<name>(<parameters>, int first, int count), a case of the fused
 * executor's dispatcher (device/dispatch.cl), and a signature the host
 * checks every launch against (kernels/embedded_programs.hpp). Parameters
 * are buffers (__global pointers), int or float; keep each declaration's
 * parameter list free of comments and parentheses. */
#ifndef ATS_TASK_H
#define ATS_TASK_H
#define ATS_TASK static inline
#endif
