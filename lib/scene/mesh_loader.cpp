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
#include "scene/ply_header.hpp"
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

// The 1-based line of vertex `index` of an ASCII PLY file whose first
// element is its vertices; 0 for any other file.
int ply_line_of_vertex(const std::string& path, std::size_t index) {
  const PlyHeader header = read_ply_header(path);
  if (header.binary || header.elements.empty() || header.elements.front().name != "vertex") return 0;
  return header.end_line + static_cast<int>(index) + 1;
}

// Vertices as the file gives them, before assimp welds or drops any (a NaN
// vertex welded into another would pass as a degenerate triangle).
void check_vertices(const aiScene& scene, const std::string& path, const std::string& where) {
  std::size_t k = 0;
  for (unsigned m = 0; m < scene.mNumMeshes; ++m) {
    const aiMesh* part = scene.mMeshes[m];
    for (unsigned i = 0; i < part->mNumVertices; ++i, ++k) {
      const aiVector3D& p = part->mVertices[i];
      const std::array<double, 3> v{p.x, p.y, p.z};
      if (!bad(v)) continue;
      int line = obj_line_of_bad_vertex(path);
      if (line == 0 && scene.mNumMeshes == 1) line = ply_line_of_vertex(path, i);
      const std::string at = line > 0 ? fmt::format("{}:{}", path, line) : fmt::format("{} (vertex {})", path, k);
      throw input_error(
          fmt::format("{}: mesh vertex at ({}, {}, {}) is not finite or further than {:g} m from the "
                      "origin (in mesh '{}', {}); fix the coordinates",
                      at, v[0], v[1], v[2], kFarthest, path, where));
    }
  }
}

[[noreturn]] void cannot_read(const std::string& path, const std::string& where, const std::string& why) {
  // assimp reports an allocation that failed as the exception's text.
  if (why.find("mNumMeshes is 0") != std::string::npos) {
    throw input_error(fmt::format("{}: mesh '{}' has no triangles; give a surface mesh with faces", where, path));
  }
  const std::string reason =
      why.find("bad_alloc") != std::string::npos
          ? "it declares more vertices or faces than memory can hold (a damaged or truncated file?)"
          : why;
  throw input_error(fmt::format("{}: cannot read mesh '{}': {}; use OBJ, PLY, STL or glTF", where, path, reason));
}

}  // namespace

TriangleMesh load_triangle_mesh(const std::string& path, const std::string& where) {
  check_input_file(path, "mesh file", where, kMaxMeshBytes);
  check_ply_counts(path, where);

  Assimp::Importer importer;
  // Drop normals, UVs and colours so JoinIdenticalVertices welds by position.
  importer.SetPropertyInteger(AI_CONFIG_PP_RVC_FLAGS, aiComponent_NORMALS | aiComponent_TANGENTS_AND_BITANGENTS |
                                                          aiComponent_COLORS | aiComponent_TEXCOORDS |
                                                          aiComponent_BONEWEIGHTS | aiComponent_ANIMATIONS |
                                                          aiComponent_TEXTURES | aiComponent_LIGHTS |
                                                          aiComponent_CAMERAS | aiComponent_MATERIALS);
  importer.SetPropertyInteger(AI_CONFIG_PP_SBP_REMOVE, aiPrimitiveType_POINT | aiPrimitiveType_LINE);
  // First as the file is (faces naming vertices it lacks are refused), then
  // welded and cleaned.
  const aiScene* raw = importer.ReadFile(path, aiProcess_ValidateDataStructure);
  if (raw == nullptr) cannot_read(path, where, importer.GetErrorString());
  check_vertices(*raw, path, where);
  const aiScene* ai =
      importer.ApplyPostProcessing(aiProcess_RemoveComponent | aiProcess_Triangulate | aiProcess_JoinIdenticalVertices |
                                   aiProcess_SortByPType | aiProcess_PreTransformVertices | aiProcess_FindDegenerates);
  if (ai == nullptr) cannot_read(path, where, importer.GetErrorString());

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
  // Node transforms (glTF) apply after the check of the file's own values.
  for (std::size_t k = 0; k < mesh.vertices.size(); ++k) {
    const auto& v = mesh.vertices[k];
    if (!bad(v)) continue;
    throw input_error(
        fmt::format("{} (vertex {}): mesh vertex at ({}, {}, {}) after the file's node transforms is not finite or "
                    "further than {:g} m from the origin ({}); fix the transforms",
                    path, k, v[0], v[1], v[2], kFarthest, where));
  }
  if (mesh.triangles.empty()) {
    throw input_error(fmt::format("{}: mesh '{}' has no triangles; give a surface mesh with faces", where, path));
  }
  return mesh;
}

}  // namespace atssim::scene
