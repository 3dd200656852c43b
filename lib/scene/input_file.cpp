#include "scene/input_file.hpp"

#include <unistd.h>

#include <filesystem>

#include <fmt/format.h>

#include "util/error.hpp"

namespace atssim::scene {

void check_input_file(const std::string& path, std::string_view kind, std::string_view where,
                      std::uintmax_t max_bytes) {
  namespace fs = std::filesystem;
  const std::string prefix =
      where.empty() ? fmt::format("{}: {}", path, kind) : fmt::format("{}: {} '{}'", where, kind, path);
  std::error_code ec;
  const fs::file_status st = fs::status(path, ec);
  if (!fs::exists(st)) {
    throw input_error(fmt::format("{} does not exist; check the path{}", prefix,
                                  where.empty() ? "" : " (relative paths are taken from the scene file's folder)"));
  }
  if (fs::is_directory(st)) throw input_error(fmt::format("{} is a folder; give a file", prefix));
  if (!fs::is_regular_file(st)) {
    throw input_error(fmt::format("{} is not a regular file (a device, pipe or socket); give a file", prefix));
  }
  const std::uintmax_t size = fs::file_size(path, ec);
  if (!ec && size > max_bytes) {
    throw input_error(fmt::format("{} is {} MiB, more than the {} MiB such a file may have; check the path", prefix,
                                  size >> 20, max_bytes >> 20));
  }
  if (::access(path.c_str(), R_OK) != 0) {
    throw input_error(fmt::format("{} cannot be read; check its permissions", prefix));
  }
}

}  // namespace atssim::scene
