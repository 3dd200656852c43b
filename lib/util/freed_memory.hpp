#pragma once
// atssim is a batch process whose frames allocate the same large scratch
// again and again: the per-frame surface record (solver/contact/
// surface_contacts) builds about 150 MB of boxes, grid and positions at
// 262K vertices, the state read and the checkpoint tens of megabytes more.
// glibc serves a block over its mmap threshold (at most 32 MB by default)
// with fresh pages and hands them back on free, and trims the heap's top,
// so each frame paid again for zeroed pages: a third of the record's wall
// time on this machine (docs/benchmarks.md, "The per-frame surface
// record"). keep_freed_memory() raises both thresholds to 1 GiB: freed
// blocks stay in the heap for the next frame, and the process's resident
// memory stays at its peak until it exits. It also makes every thread
// allocate from the one main heap (M_ARENA_MAX 1): `atssim run` measures
// the record on a thread of its own, and a thread's own glibc arena lives
// in heaps of at most 64 MB that glibc unmaps whole once they are free,
// whatever the thresholds, so the record's scratch came back as fresh
// pages every frame all the same (on the 262K drape 450-630 ms a frame
// against 250-310 ms with one heap; docs/benchmarks.md). Call it before
// any thread allocates.
namespace atssim::util {

// Returns false where the C library refused a setting (or is not glibc).
bool keep_freed_memory();

}  // namespace atssim::util
