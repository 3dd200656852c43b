#include "scene/tet_mesh_loader.hpp"

#include <cctype>
#include <filesystem>
#include <fstream>

#include <fmt/format.h>

#include "scene/gmsh_reader.hpp"
#include "scene/tetgen_reader.hpp"
#include "util/error.hpp"

namespace atssim::scene {

namespace {

namespace fs = std::filesystem;

std::string extension_of(const std::string& path) {
  std::string ext = fs::path(path).extension().string();
  for (char& c : ext) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  return ext;
}

void require_readable(const std::string& path, const std::string& where, std::string_view role) {
  std::error_code ec;
  if (!fs::exists(path, ec)) {
    throw input_error(
        fmt::format("{}: {} '{}' does not exist; fix the path (relative paths are taken from the "
                    "scene file's folder)",
                    where, role, path));
  }
  if (!fs::is_regular_file(path, ec) || !std::ifstream(path).good()) {
    throw input_error(fmt::format("{}: {} '{}' cannot be read; check that it is a readable file", where, role, path));
  }
}

// Drops vertices no tetrahedron names, so none becomes a massless particle.
void drop_unused_vertices(TetMesh& mesh) {
  std::vector<int> index(mesh.vertices.size(), -1);
  for (const auto& t : mesh.tetrahedra) {
    for (int v : t) index[v] = 0;
  }
  std::vector<std::array<double, 3>> kept;
  for (std::size_t v = 0; v < mesh.vertices.size(); ++v) {
    if (index[v] < 0) continue;
    index[v] = static_cast<int>(kept.size());
    kept.push_back(mesh.vertices[v]);
  }
  if (kept.size() == mesh.vertices.size()) return;
  mesh.vertices = std::move(kept);
  for (auto& t : mesh.tetrahedra) {
    for (int& v : t) v = index[v];
  }
}

}  // namespace

bool is_tet_mesh_path(const std::string& path) {
  const std::string ext = extension_of(path);
  return ext == ".node" || ext == ".ele" || ext == ".msh";
}

TetMesh load_tet_mesh(const std::string& path, const std::string& where) {
  const std::string ext = extension_of(path);
  TetMesh mesh;
  if (ext == ".node" || ext == ".ele") {
    const std::string node = fs::path(path).replace_extension(".node").string();
    const std::string ele = fs::path(path).replace_extension(".ele").string();
    require_readable(node, where, "TetGen point file");
    require_readable(ele, where, "TetGen element file");
    mesh = read_tetgen(node, ele);
  } else if (ext == ".msh") {
    require_readable(path, where, "Gmsh mesh");
    mesh = read_gmsh(path);
  } else {
    throw input_error(
        fmt::format("{}: '{}' is not a tetrahedral mesh format atssim reads; give a TetGen .node/.ele "
                    "pair or a Gmsh .msh (ASCII 2.2 or 4.1)",
                    where, path));
  }
  drop_unused_vertices(mesh);
  return mesh;
}

}  // namespace atssim::scene
