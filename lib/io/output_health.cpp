#include "io/output_health.hpp"

#include <sys/stat.h>
#include <sys/statvfs.h>
#include <unistd.h>

#include <filesystem>

#include <fmt/format.h>

#include "util/error.hpp"

namespace atssim::io {

std::string partial_path(const std::string& path) {
  std::filesystem::path p(path);
  // Without an extension the sidecars would collide ("out" and "out.partial" -> "out.xdmf").
  const std::string ext = p.has_extension() ? p.extension().string() : std::string(".h5");
  return p.replace_extension().string() + ".partial" + ext;
}

void check_output_folder(const std::string& path) {
  if (path.empty()) throw input_error("the output path is empty: pass -o FILE.h5 or set output.path");
  const std::filesystem::path p(path);
  std::error_code ec;
  if (std::filesystem::is_directory(p, ec)) {
    throw input_error(fmt::format("output '{}' is a folder: pass -o with a file name, e.g. -o {}/run.h5", path, path));
  }
  const std::filesystem::path folder = p.has_parent_path() ? p.parent_path() : std::filesystem::path(".");
  if (!std::filesystem::is_directory(folder, ec)) {
    throw input_error(
        fmt::format("cannot create output file '{}': its folder '{}' does not exist (make it, or pass "
                    "-o elsewhere)",
                    path, folder.string()));
  }
  if (::access(folder.c_str(), W_OK) != 0) {
    throw input_error(
        fmt::format("cannot create output file '{}': its folder '{}' is not writable (pass -o "
                    "elsewhere)",
                    path, folder.string()));
  }
  if (std::filesystem::exists(p, ec) && !std::filesystem::is_regular_file(p, ec)) {
    throw input_error(fmt::format("output '{}' exists and is not a regular file: pass -o elsewhere", path));
  }
  std::filesystem::path stem = p;
  if (p.extension() == ".xdmf") {
    throw input_error(
        fmt::format("output '{}' ends in .xdmf, the name of its XDMF sidecar; pass the HDF5 file's name, e.g. -o {}",
                    path, stem.replace_extension(".h5").string()));
  }
  // The files beside it: the sidecar, the lock, and (over an earlier
  // result) the partial file and its sidecar.
  for (const std::filesystem::path& beside :
       {std::filesystem::path(p).replace_extension(".xdmf"), std::filesystem::path(path + ".lock"),
        std::filesystem::path(partial_path(path)),
        std::filesystem::path(partial_path(path)).replace_extension(".xdmf")}) {
    if (std::filesystem::exists(beside, ec) && !std::filesystem::is_regular_file(beside, ec)) {
      throw input_error(
          fmt::format("output '{}': '{}', which the run writes beside it, exists and is not a regular "
                      "file; remove it or pass -o elsewhere",
                      path, beside.string()));
    }
  }
}

OutputIdentity identify_output(const std::string& path) {
  struct stat st {};
  if (::stat(path.c_str(), &st) != 0) return {};
  return {static_cast<unsigned long long>(st.st_dev), static_cast<unsigned long long>(st.st_ino)};
}

void check_output_health(const std::string& path, const OutputIdentity& opened, std::size_t frame_bytes) {
  struct stat st {};
  if (::stat(path.c_str(), &st) != 0 || st.st_dev != opened.device || st.st_ino != opened.inode) {
    throw runtime_error(
        fmt::format("the output file '{}' (or its folder) was removed or replaced during the run", path));
  }
  // Stop before the disk is full rather than in the middle of a flush: a
  // write that fails half-way can leave the metadata of the last good flush
  // pointing at space that was never written.
  struct statvfs fs {};
  const std::filesystem::path p(path);
  const std::string folder = p.has_parent_path() ? p.parent_path().string() : std::string(".");
  if (::statvfs(folder.c_str(), &fs) == 0) {
    const unsigned long long free_bytes = static_cast<unsigned long long>(fs.f_bavail) * fs.f_frsize;
    const unsigned long long needed = 2ull * frame_bytes + (1ull << 20);
    if (free_bytes < needed) {
      throw runtime_error(fmt::format("the disk of '{}' is full ({} KiB free, a frame needs ~{} KiB with margin)", path,
                                      free_bytes / 1024, needed / 1024));
    }
  }
}

}  // namespace atssim::io
