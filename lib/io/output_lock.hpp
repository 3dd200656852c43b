#pragma once
// One writer per output path: an exclusive flock(2) on `<path>.lock`, taken
// before the output is created or truncated (HDF5 truncates a file before
// its own lock could refuse the open). The kernel drops the lock when the
// process ends, however it ends, so a killed run never blocks the next one.
#include <string>

namespace atssim::io {

class OutputLock {
 public:
  // Throws atssim::Error (input) naming the path when another process holds
  // it, and (runtime) when the lock file cannot be made.
  explicit OutputLock(const std::string& output_path);
  OutputLock(const OutputLock&) = delete;
  OutputLock& operator=(const OutputLock&) = delete;
  ~OutputLock();  // removes the lock file, then unlocks

  const std::string& lock_path() const { return lock_path_; }

 private:
  std::string lock_path_;
  int fd_ = -1;
};

}  // namespace atssim::io
