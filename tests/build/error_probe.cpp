// An atssim::Error with and without its kind (tests/build/CMakeLists.txt).
#include "util/error.hpp"

atssim::Error probe() {
#if ATSSIM_PROBE_NO_KIND
  return atssim::Error("a message without a kind");
#else
  return atssim::Error("a message with a kind", atssim::ErrorKind::internal);
#endif
}
