#include "scene/mesh_loader.hpp"

#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>

#include <assimp/postprocess.h>
#include <assimp/scene.h>
#include <fmt/format.h>
#include <assimp/Importer.hpp>

#include "scene/input_file.hpp"
#include "util/error.hpp"

namespace atssim::scene {

namespace {

constexpr double kFarthest = 1e8;  // m: float32 positions lose all precision beyond

bool bad(const std::array<double, 3>& v) {
  for (double c : v) {
    if (!std::isfinite(c) || std::abs(c) > kFarthest) return true;
  }
  return false;
}

// The 1-based line of the `index`-th vertex line ("v x y z") of an OBJ file
// whose coordinates are not finite or absurd; 0 when not found.
int obj_line_of_bad_vertex(const std::string& path) {
  std::ifstream in(path);
  int line = 0;
  for (std::string l; std::getline(in, l);) {
    ++line;
    if (l.size() < 2 || l[0] != 'v' || (l[1] != ' ' && l[1] != '\t')) continue;
    std::istringstream fields(l.substr(1));
    std::array<double, 3> v{};
    std::string word;
    for (double& c : v) {
      if (!(fields >> word)) break;
      c = std::strtod(word.c_str(), nullptr);
    }
    if (bad(v)) return line;
  }
  return 0;
}

void check_vertices(const TriangleMesh& mesh, const std::string& path, const std::string& where) {
  for (std::size_t k = 0; k < mesh.vertices.size(); ++k) {
    const auto& v = mesh.vertices[k];
    if (!bad(v)) continue;
    const int line = obj_line_of_bad_vertex(path);
    const std::string at = line > 0 ? fmt::format("{}:{}", path, line) : fmt::format("{} (vertex {})", path, k);
    throw input_error(
        fmt::format("{}: mesh vertex at ({}, {}, {}) is not finite or further than {:g} m from the "
                    "origin (in mesh '{}', {}); fix the coordinates",
                    at, v[0], v[1], v[2], kFarthest, path, where));
  }
}

}  // namespace

TriangleMesh load_triangle_mesh(const std::string& path, const std::string& where) {
  check_input_file(path, "mesh file", where, kMaxMeshBytes);

  Assimp::Importer importer;
  // Drop normals, UVs and colours so JoinIdenticalVertices welds by position.
  importer.SetPropertyInteger(AI_CONFIG_PP_RVC_FLAGS, aiComponent_NORMALS | aiComponent_TANGENTS_AND_BITANGENTS |
                                                          aiComponent_COLORS | aiComponent_TEXCOORDS |
                                                          aiComponent_BONEWEIGHTS | aiComponent_ANIMATIONS |
                                                          aiComponent_TEXTURES | aiComponent_LIGHTS |
                                                          aiComponent_CAMERAS | aiComponent_MATERIALS);
  importer.SetPropertyInteger(AI_CONFIG_PP_SBP_REMOVE, aiPrimitiveType_POINT | aiPrimitiveType_LINE);
  const aiScene* ai =
      importer.ReadFile(path, aiProcess_RemoveComponent | aiProcess_Triangulate | aiProcess_JoinIdenticalVertices |
                                  aiProcess_SortByPType | aiProcess_PreTransformVertices | aiProcess_FindDegenerates);
  if (ai == nullptr) {
    throw input_error(fmt::format("{}: cannot read mesh '{}': {}; use OBJ, PLY, STL or glTF", where, path,
                                  importer.GetErrorString()));
  }

  TriangleMesh mesh;
  for (unsigned m = 0; m < ai->mNumMeshes; ++m) {
    const aiMesh* part = ai->mMeshes[m];
    if ((part->mPrimitiveTypes & aiPrimitiveType_TRIANGLE) == 0) continue;
    const int offset = static_cast<int>(mesh.vertices.size());
    for (unsigned v = 0; v < part->mNumVertices; ++v) {
      const aiVector3D& p = part->mVertices[v];
      mesh.vertices.push_back({p.x, p.y, p.z});
    }
    for (unsigned f = 0; f < part->mNumFaces; ++f) {
      const aiFace& face = part->mFaces[f];
      if (face.mNumIndices != 3) continue;
      mesh.triangles.push_back({offset + static_cast<int>(face.mIndices[0]),
                                offset + static_cast<int>(face.mIndices[1]),
                                offset + static_cast<int>(face.mIndices[2])});
    }
  }
  check_vertices(mesh, path, where);
  if (mesh.triangles.empty()) {
    throw input_error(fmt::format("{}: mesh '{}' has no triangles; give a surface mesh with faces", where, path));
  }
  return mesh;
}

}  // namespace atssim::scene
