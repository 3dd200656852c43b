#pragma once
// Shared virtual memory allocations of one context (internal to lib/device).
// Coarse-grain buffers are touched by the host only between map and unmap;
// fine-grain buffers directly, once the queues are finished.
#include <cstddef>
#include <vector>

#include "device/opencl.hpp"

namespace atssim::device {

class SvmArena {
 public:
  // `atomics`: fine-grain buffers that kernels and the host may update
  // atomically while kernels run (the fused executor's counters).
  SvmArena(cl::Context context, bool fine_grain, bool atomics = false);
  SvmArena(const SvmArena&) = delete;
  SvmArena& operator=(const SvmArena&) = delete;
  ~SvmArena();

  bool fine_grain() const { return fine_grain_; }
  // Allocates at least `bytes` (≥ 16), 64-byte aligned, zero-filled when
  // fine grain.
  void* allocate(std::size_t bytes);
  // Frees one allocation of this arena (no kernel may still use it).
  void release(void* ptr);
  // Host copies through `queue` (blocking map/unmap for coarse grain).
  void write(const cl::CommandQueue& queue, void* ptr, const void* src, std::size_t bytes);
  void read(const cl::CommandQueue& queue, const void* ptr, void* dst, std::size_t bytes);

 private:
  cl::Context context_;
  bool fine_grain_;
  bool atomics_;
  std::vector<void*> allocations_;
};

}  // namespace atssim::device
