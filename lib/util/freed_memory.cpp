#include "util/freed_memory.hpp"

#include <cstdlib>  // (defines __GLIBC__ where it is glibc)

#if defined(__GLIBC__)
#include <malloc.h>
#endif

namespace atssim::util {

bool keep_freed_memory() {
#if defined(__GLIBC__)
  constexpr int kThreshold = 1 << 30;
  return mallopt(M_MMAP_THRESHOLD, kThreshold) == 1 && mallopt(M_TRIM_THRESHOLD, kThreshold) == 1 &&
         mallopt(M_ARENA_MAX, 1) == 1;
#else
  return false;
#endif
}

}  // namespace atssim::util
