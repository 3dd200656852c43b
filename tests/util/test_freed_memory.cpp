#include <catch2/catch.hpp>

#include <cstdlib>
#include <cstring>
#include <thread>

#include <unistd.h>

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

namespace {

// Keeps freed memory (util::keep_freed_memory); false in an ASan build,
// whose allocator stands in for glibc's: there is no glibc heap to keep
// blocks in, and the call must only do no harm.
bool kept() {
  [[maybe_unused]] const bool done = util::keep_freed_memory();
#if defined(ATSSIM_ASAN)
  WARN("an ASan build: glibc's heap is not in use, nothing to measure");
  return false;
#else
  REQUIRE(done);
  return true;
#endif
}

}  // namespace

TEST_CASE("freed blocks of tens of megabytes stay in the heap for the next frame once kept", "[util][freed_memory]") {
  // 64 MB, over glibc's largest default mmap threshold (32 MB): by default
  // it is mapped on its own and unmapped on free, so the heap's free bytes
  // (mallinfo2().fordblks) never hold it.
  constexpr std::size_t kBytes = std::size_t(64) << 20;
  if (!kept()) return;
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

TEST_CASE("once kept, a block another thread allocates comes from the main heap, which keeps it",
          "[util][freed_memory]") {
  // glibc gives a second thread an arena of its own: heaps mapped apart
  // from the main heap (above the program break) and unmapped whole once
  // free, whatever the thresholds. Kept, the thread allocates from the
  // main heap, which lies below the break.
  constexpr std::size_t kBytes = std::size_t(40) << 20;  // under an arena heap's 64 MB
  if (!kept()) return;
  bool below_break = false, allocated = false;
  std::thread other([&] {
    void* block = std::malloc(kBytes);
    allocated = block != nullptr;
    if (!allocated) return;
    std::memset(block, 1, kBytes);
    below_break = static_cast<char*>(block) + kBytes <= static_cast<char*>(sbrk(0));
    std::free(block);
  });
  other.join();
  REQUIRE(allocated);
  CHECK(below_break);
}
