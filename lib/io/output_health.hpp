#pragma once
// Where a run writes and whether it still can: the checks that end a run
// with one line (docs/reliability.md) before HDF5 meets a missing folder, a
// replaced file or a full disk in the middle of a flush.
#include <cstddef>
#include <string>

namespace atssim::io {

// "out.h5" -> "out.partial.h5" ("out" -> "out.partial.h5"): where a run
// writes while an earlier result is at the path.
std::string partial_path(const std::string& path);

// Throws an input error (exit 2) when `path` cannot become an output file:
// empty, a folder, in a folder that is missing or not writable, an existing
// non-regular file, a name ending in .xdmf (its own sidecar's), or a path
// whose sidecar, lock or partial file would land on a folder or device.
void check_output_folder(const std::string& path);

// The file a run writes, by device and inode, to notice it vanish or be replaced.
struct OutputIdentity {
  unsigned long long device = 0, inode = 0;
};
OutputIdentity identify_output(const std::string& path);

// Throws a runtime error (exit 1) when `path` is no longer the file that was
// opened, or its disk has less free space than two frames of `frame_bytes`
// and a MiB of margin.
void check_output_health(const std::string& path, const OutputIdentity& opened, std::size_t frame_bytes);

}  // namespace atssim::io
