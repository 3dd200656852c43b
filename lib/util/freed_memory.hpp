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
// memory stays at its peak until it exits.
namespace atssim::util {

// Returns false where the C library refused a setting (or is not glibc).
bool keep_freed_memory();

}  // namespace atssim::util
