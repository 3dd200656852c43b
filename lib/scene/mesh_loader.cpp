#include "scene/mesh_loader.hpp"

#include <filesystem>
#include <fstream>

#include <assimp/Importer.hpp>
#include <assimp/postprocess.h>
#include <assimp/scene.h>
#include <fmt/format.h>

#include "util/error.hpp"

namespace atssim::scene {

TriangleMesh load_triangle_mesh(const std::string& path, const std::string& where) {
  namespace fs = std::filesystem;
  std::error_code ec;
  if (!fs::exists(path, ec)) {
    throw input_error(fmt::format("{}: mesh file '{}' does not exist; fix the path (relative paths are "
                                  "taken from the scene file's folder)", where, path));
  }
  if (!fs::is_regular_file(path, ec) || !std::ifstream(path).good()) {
    throw input_error(fmt::format("{}: mesh file '{}' cannot be read; check that it is a readable file",
                                  where, path));
  }

  Assimp::Importer importer;
  // Drop normals, UVs and colours so JoinIdenticalVertices welds by position.
  importer.SetPropertyInteger(AI_CONFIG_PP_RVC_FLAGS,
                              aiComponent_NORMALS | aiComponent_TANGENTS_AND_BITANGENTS |
                                  aiComponent_COLORS | aiComponent_TEXCOORDS |
                                  aiComponent_BONEWEIGHTS | aiComponent_ANIMATIONS |
                                  aiComponent_TEXTURES | aiComponent_LIGHTS | aiComponent_CAMERAS |
                                  aiComponent_MATERIALS);
  importer.SetPropertyInteger(AI_CONFIG_PP_SBP_REMOVE, aiPrimitiveType_POINT | aiPrimitiveType_LINE);
  const aiScene* ai = importer.ReadFile(
      path, aiProcess_RemoveComponent | aiProcess_Triangulate | aiProcess_JoinIdenticalVertices |
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
  if (mesh.triangles.empty()) {
    throw input_error(fmt::format("{}: mesh '{}' has no triangles; give a surface mesh with faces",
                                  where, path));
  }
  return mesh;
}

}  // namespace atssim::scene
