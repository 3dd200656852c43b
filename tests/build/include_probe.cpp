// Includes ATSSIM_PROBE_HEADER (set by tests/build/CMakeLists.txt) with the
// include roots of the library the case links.
#include ATSSIM_PROBE_HEADER
