#pragma once
// The counts a PLY header declares, against the bytes the file holds after
// it: a header that declares more vertices or faces than the file can hold
// is refused before assimp allocates for them (2e9 faces are 32 GB of
// aiFace, which a sanitizer build cannot even try to allocate).
#include <cstdint>
#include <string>
#include <vector>

namespace atssim::scene {

struct PlyElement {
  std::string name;
  std::uint64_t count = 0;
  std::uint64_t min_bytes = 0;  // the least one item can take in the file's format
  int line = 0;                 // 1-based line of its "element" line
};

struct PlyHeader {
  bool binary = false;
  std::uint64_t header_bytes = 0;  // through the newline after end_header
  int end_line = 0;                // 1-based line of end_header
  std::vector<PlyElement> elements;
};

// The header of the PLY file at `path`; no elements when the file is no PLY
// or its header cannot be read (assimp then says why).
PlyHeader read_ply_header(const std::string& path);

// Throws an input error naming `where`, the file and the element whose count
// the bytes after the header cannot hold; does nothing for any other file.
void check_ply_counts(const std::string& path, const std::string& where);

}  // namespace atssim::scene
