#include "scene/ply_header.hpp"

#include <cerrno>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>

#include <fmt/format.h>

#include "util/error.hpp"

namespace atssim::scene {

namespace {

constexpr int kMaxHeaderLines = 10000;

// Bytes of a PLY scalar type; 0 for a name that is none.
std::uint64_t scalar_bytes(const std::string& type) {
  if (type == "char" || type == "uchar" || type == "int8" || type == "uint8") return 1;
  if (type == "short" || type == "ushort" || type == "int16" || type == "uint16") return 2;
  if (type == "int" || type == "uint" || type == "int32" || type == "uint32" || type == "float" || type == "float32")
    return 4;
  if (type == "double" || type == "float64") return 8;
  return 0;
}

}  // namespace

PlyHeader read_ply_header(const std::string& path) {
  PlyHeader header;
  std::ifstream in(path, std::ios::binary);
  std::string l;
  if (!std::getline(in, l) || l.rfind("ply", 0) != 0) return header;
  std::vector<PlyElement> elements;
  for (int line = 2; line <= kMaxHeaderLines && std::getline(in, l); ++line) {
    if (!l.empty() && l.back() == '\r') l.pop_back();
    std::istringstream words(l);
    std::string word;
    words >> word;
    if (word == "format") {
      words >> word;
      header.binary = word != "ascii";
    } else if (word == "element") {
      PlyElement e;
      std::string count;
      words >> e.name >> count;
      errno = 0;
      char* end = nullptr;
      e.count = std::strtoull(count.c_str(), &end, 10);
      if (count.empty() || *end != '\0' || errno != 0 || count[0] == '-') return header;
      e.line = line;
      elements.push_back(e);
    } else if (word == "property") {
      if (elements.empty()) return header;
      std::string type;
      words >> type;
      // A list: its count, at least (it may hold no item); in ASCII every
      // value takes a digit and a separator at least.
      const std::uint64_t bytes = type == "list" ? (words >> type, scalar_bytes(type)) : scalar_bytes(type);
      if (bytes == 0) return header;
      elements.back().min_bytes += header.binary ? bytes : 2;
    } else if (word == "end_header") {
      const auto at = in.tellg();
      if (at < 0) return header;
      header.header_bytes = static_cast<std::uint64_t>(at);
      header.end_line = line;
      header.elements = std::move(elements);
      return header;
    }
  }
  return header;
}

void check_ply_counts(const std::string& path, const std::string& where) {
  const PlyHeader header = read_ply_header(path);
  if (header.elements.empty()) return;
  std::error_code ec;
  const std::uintmax_t size = std::filesystem::file_size(path, ec);
  if (ec || size < header.header_bytes) return;
  // The last ASCII value needs no separator after it.
  const double held = static_cast<double>(size - header.header_bytes) + (header.binary ? 0.0 : 1.0);
  double needed = 0.0;
  for (const PlyElement& e : header.elements) {
    needed += static_cast<double>(e.count) * static_cast<double>(e.min_bytes);
    if (needed <= held) continue;
    throw input_error(fmt::format(
        "{}: cannot read mesh '{}': its header (line {}) declares {} '{}' elements, which the {} bytes after "
        "the header cannot hold (a damaged or truncated file?); fix the count or the file",
        where, path, e.line, e.count, e.name, size - header.header_bytes));
  }
}

}  // namespace atssim::scene
