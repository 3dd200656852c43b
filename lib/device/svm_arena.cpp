#include "device/svm_arena.hpp"

#include <algorithm>
#include <cstring>

#include <fmt/format.h>

#include "util/error.hpp"

namespace atssim::device {

SvmArena::SvmArena(cl::Context context, bool fine_grain, bool atomics)
    : context_(std::move(context)), fine_grain_(fine_grain || atomics), atomics_(atomics) {}

SvmArena::~SvmArena() {
  for (void* p : allocations_) clSVMFree(context_(), p);
}

void* SvmArena::allocate(std::size_t bytes) {
  cl_svm_mem_flags flags = CL_MEM_READ_WRITE;
  if (fine_grain_) flags |= CL_MEM_SVM_FINE_GRAIN_BUFFER;
  if (atomics_) flags |= CL_MEM_SVM_ATOMICS;
  const std::size_t size = std::max<std::size_t>(bytes, 16);
  void* p = clSVMAlloc(context_(), flags, size, 64);
  if (p == nullptr) {
    throw runtime_error(
        fmt::format("cannot allocate {} bytes of shared virtual memory on the device; make the "
                    "scene smaller or choose another device",
                    bytes));
  }
  if (fine_grain_) std::memset(p, 0, size);
  allocations_.push_back(p);
  return p;
}

void SvmArena::release(void* ptr) {
  const auto it = std::find(allocations_.begin(), allocations_.end(), ptr);
  if (it == allocations_.end()) return;
  clSVMFree(context_(), ptr);
  allocations_.erase(it);
}

void SvmArena::write(const cl::CommandQueue& queue, void* ptr, const void* src, std::size_t bytes) {
  if (bytes == 0) return;
  if (fine_grain_) {
    std::memcpy(ptr, src, bytes);
    return;
  }
  check_cl(clEnqueueSVMMap(queue(), CL_TRUE, CL_MAP_WRITE_INVALIDATE_REGION, ptr, bytes, 0, nullptr, nullptr),
           "mapping SVM for writing");
  std::memcpy(ptr, src, bytes);
  check_cl(clEnqueueSVMUnmap(queue(), ptr, 0, nullptr, nullptr), "unmapping SVM");
  check_cl(clFinish(queue()), "finishing the queue after an SVM write");
}

void SvmArena::read(const cl::CommandQueue& queue, const void* ptr, void* dst, std::size_t bytes) {
  if (bytes == 0) return;
  void* p = const_cast<void*>(ptr);
  if (fine_grain_) {
    check_cl(clFinish(queue()), "finishing the queue before an SVM read");
    std::memcpy(dst, p, bytes);
    return;
  }
  check_cl(clEnqueueSVMMap(queue(), CL_TRUE, CL_MAP_READ, p, bytes, 0, nullptr, nullptr), "mapping SVM for reading");
  std::memcpy(dst, p, bytes);
  check_cl(clEnqueueSVMUnmap(queue(), p, 0, nullptr, nullptr), "unmapping SVM");
  check_cl(clFinish(queue()), "finishing the queue after an SVM read");
}

}  // namespace atssim::device
