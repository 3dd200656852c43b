#pragma once
// Reads Gmsh .msh files, formats 2.2 and 4.1 ASCII (Gmsh reference manual,
// "MSH file format"). Only the format is read; Gmsh (GPL) is not used.
#include <string>

#include "scene/scene_desc.hpp"

namespace atssim::scene {

// Keeps the nodes and the 4-node tetrahedra (element type 4); every other
// element type (points, lines, surface triangles, …) is skipped. Node tags
// may be sparse: they are remapped to 0…n-1 in the order of $Nodes. Binary
// files and other versions are input errors that say how to export ASCII
// 4.1 or 2.2; every error names the file and line.
TetMesh read_gmsh(const std::string& path);

}  // namespace atssim::scene
