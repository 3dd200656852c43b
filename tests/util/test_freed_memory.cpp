#include <catch2/catch.hpp>

#include <cstdlib>
#include <cstring>

#include <malloc.h>

#include "util/freed_memory.hpp"

using namespace atssim;

#if defined(__SANITIZE_ADDRESS__)
#define ATSSIM_ASAN 1
#elif defined(__has_feature)
#if __has_feature(address_sanitizer)
#define ATSSIM_ASAN 1
#endif
#endif

TEST_CASE("freed blocks of tens of megabytes stay in the heap for the next frame once kept", "[util][freed_memory]") {
  // 64 MB, over glibc's largest default mmap threshold (32 MB): by default
  // it is mapped on its own and unmapped on free, so the heap's free bytes
  // (mallinfo2().fordblks) never hold it.
  constexpr std::size_t kBytes = std::size_t(64) << 20;
#if defined(ATSSIM_ASAN)
  // AddressSanitizer's allocator stands in for glibc's: there is no glibc
  // heap to keep blocks in, and the call must only do no harm.
  util::keep_freed_memory();
  WARN("an ASan build: glibc's heap is not in use, nothing to measure");
  return;
#endif
  REQUIRE(util::keep_freed_memory());
  void* block = std::malloc(kBytes);
  REQUIRE(block != nullptr);
  std::memset(block, 1, kBytes);  // touched, as a frame's scratch is
  const std::size_t mapped_before = mallinfo2().hblkhd;
  std::free(block);
  const struct mallinfo2 after = mallinfo2();
  CHECK(after.fordblks >= kBytes);       // kept as free heap memory
  CHECK(after.hblkhd <= mapped_before);  // and it was never a mapping of its own
  CHECK(mapped_before < kBytes);
}
