#pragma once
// Reads triangle meshes through assimp (OBJ, PLY, STL, glTF/GLB, …).
#include <string>

#include "scene/scene_desc.hpp"

namespace atssim::scene {

// Loads every mesh of the file into one TriangleMesh, welding vertices that
// share a position (UV or normal seams must not tear the cloth). Throws
// atssim::Error (prefixed with `where`, e.g. "scene.yaml:12") when the file
// is missing, unreadable, not a mesh assimp knows, or has no triangles.
TriangleMesh load_triangle_mesh(const std::string& path, const std::string& where);

}  // namespace atssim::scene
