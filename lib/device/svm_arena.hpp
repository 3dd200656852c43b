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
  SvmArena(cl::Context context, bool fine_grain);
  SvmArena(const SvmArena&) = delete;
  SvmArena& operator=(const SvmArena&) = delete;
  ~SvmArena();

  bool fine_grain() const { return fine_grain_; }
  // Allocates at least `bytes` (≥ 16), 64-byte aligned.
  void* allocate(std::size_t bytes);
  // Host copies through `queue` (blocking map/unmap for coarse grain).
  void write(const cl::CommandQueue& queue, void* ptr, const void* src, std::size_t bytes);
  void read(const cl::CommandQueue& queue, const void* ptr, void* dst, std::size_t bytes);

 private:
  cl::Context context_;
  bool fine_grain_;
  std::vector<void*> allocations_;
};

}  // namespace atssim::device
