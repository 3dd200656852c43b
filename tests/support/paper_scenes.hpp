#pragma once
// The paper's Table-1 scenes at the paper's size (scenes/paper/NAME.yaml)
// for tests: their meshes (scenes/paper/meshes/large/, not committed) are
// written by scripts/make_meshes.py into a copy of the scene folder under a
// temp dir, so a test never reads meshes an older generator left in the
// source tree, and the counts docs/scenes.md states for each scene.
#include <algorithm>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <regex>
#include <sstream>
#include <stdexcept>
#include <string>
#include <vector>

#include "support/temp_dir.hpp"

namespace atssim::test {

// scenes/paper/*.yaml without the _small ones, found on disk (a scene added
// there is tested too), sorted.
inline std::vector<std::string> paper_size_scenes() {
  std::vector<std::string> found;
  for (const auto& e : std::filesystem::directory_iterator(std::filesystem::path(ATSSIM_SOURCE_DIR) / "scenes/paper")) {
    const std::string stem = e.path().stem().string();
    if (e.path().extension() == ".yaml" && !stem.ends_with("_small")) found.push_back(stem);
  }
  std::sort(found.begin(), found.end());
  return found;
}

// dir/scenes/paper/NAME.yaml for every scene of scenes/paper, dir/scenes/meshes
// a link to the bundled obstacle meshes (the scenes name ../meshes/...), and
// the paper-size meshes written by scripts/make_meshes.py --paper into
// dir/scenes/paper/meshes (~2 s). Returns dir/scenes/paper.
inline std::filesystem::path paper_scene_copy(const TempDir& dir) {
  namespace fs = std::filesystem;
  const fs::path source = fs::path(ATSSIM_SOURCE_DIR) / "scenes";
  const fs::path paper = dir.path() / "scenes" / "paper";
  fs::create_directories(paper);
  fs::create_directory_symlink(source / "meshes", dir.path() / "scenes" / "meshes");
  for (const auto& e : fs::directory_iterator(source / "paper")) {
    if (e.path().extension() == ".yaml") fs::copy_file(e.path(), paper / e.path().filename());
  }
  const std::string cmd = "/usr/bin/python3 " + (fs::path(ATSSIM_SOURCE_DIR) / "scripts/make_meshes.py").string() +
                          " --paper " + (paper / "meshes").string() + " >" + dir.file("make_meshes.log") + " 2>&1";
  if (std::system(cmd.c_str()) != 0) throw std::runtime_error("scripts/make_meshes.py --paper failed: " + cmd);
  return paper;
}

// What docs/scenes.md's table of the paper's scenes says of one scene, at
// the paper's size (`small` false) or the small variant's: vertices,
// triangles (of the cloths) and tetrahedra, 0 where the cell names none.
struct StatedSize {
  long long vertices = -1, triangles = 0, tetrahedra = 0;
};

inline StatedSize stated_size(const std::string& scene, bool small) {
  std::ifstream in(std::filesystem::path(ATSSIM_SOURCE_DIR) / "docs/scenes.md");
  std::string line;
  bool in_table = false;  // the table of the paper's scenes, after its header
  while (std::getline(in, line)) {
    if (line.rfind("| scene | paper (Table 1) |", 0) == 0) in_table = true;
    if (!in_table || line.rfind("| " + scene + " |", 0) != 0) continue;
    // | scene | paper | here, paper size | here, small | ...
    std::vector<std::string> cells;
    std::stringstream s(line);
    std::string cell;
    while (std::getline(s, cell, '|')) cells.push_back(cell);
    if (cells.size() < 5) break;
    StatedSize out;
    const std::string text = cells[small ? 4 : 3];
    static const std::regex count(R"(([0-9][0-9 ]*[0-9]|[0-9]) (v|tris|cloth tris|tets)\b)");
    for (std::sregex_iterator m(text.begin(), text.end(), count), end; m != end; ++m) {
      std::string digits = (*m)[1].str();
      digits.erase(std::remove(digits.begin(), digits.end(), ' '), digits.end());
      const long long n = std::stoll(digits);
      const std::string unit = (*m)[2].str();
      (unit == "v" ? out.vertices : unit == "tets" ? out.tetrahedra : out.triangles) = n;
    }
    return out;
  }
  return {};
}

}  // namespace atssim::test
