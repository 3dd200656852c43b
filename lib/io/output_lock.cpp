#include "io/output_lock.hpp"

#include <fcntl.h>
#include <sys/file.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>
#include <string>

#include <fmt/format.h>

#include "util/error.hpp"

namespace atssim::io {

OutputLock::OutputLock(const std::string& output_path) : lock_path_(output_path + ".lock") {
  // A holder removes the file before unlocking; whoever locked the removed
  // file retries on the new one (the inode check), so two never both hold it.
  for (int attempt = 0; attempt < 100; ++attempt) {
    const int fd = ::open(lock_path_.c_str(), O_RDWR | O_CREAT | O_CLOEXEC, 0644);
    if (fd < 0) {
      const int err = errno;
      // A place that cannot hold files (a read-only or pseudo file system,
      // no permission, a folder in the way) is the output path's fault.
      const bool path_fault = err == EACCES || err == EPERM || err == EROFS || err == ENOENT || err == ENOTDIR ||
                              err == EISDIR || err == ENAMETOOLONG || err == ELOOP;
      const std::string what =
          fmt::format("cannot create the lock file '{}' beside the output: {}", lock_path_, std::strerror(err));
      if (path_fault) throw input_error(what + "; pass -o elsewhere");
      throw runtime_error(what);
    }
    if (::flock(fd, LOCK_EX | LOCK_NB) != 0) {
      const int err = errno;
      ::close(fd);
      if (err == EWOULDBLOCK) {
        throw input_error(
            fmt::format("{}: another atssim run is writing this output (it holds {}); wait for it to end or pass -o "
                        "elsewhere",
                        output_path, lock_path_));
      }
      throw runtime_error(fmt::format("cannot lock '{}': {}", lock_path_, std::strerror(err)));
    }
    struct stat held {
    }, named{};
    if (::fstat(fd, &held) == 0 && ::stat(lock_path_.c_str(), &named) == 0 && held.st_ino == named.st_ino &&
        held.st_dev == named.st_dev) {
      fd_ = fd;
      const std::string pid = std::to_string(::getpid()) + "\n";
      if (::ftruncate(fd, 0) == 0) (void)!::write(fd, pid.data(), pid.size());
      return;
    }
    ::close(fd);
  }
  throw runtime_error(fmt::format("cannot lock '{}': it keeps being replaced", lock_path_));
}

OutputLock::~OutputLock() {
  if (fd_ < 0) return;
  ::unlink(lock_path_.c_str());
  ::close(fd_);
}

}  // namespace atssim::io
