#pragma once
// Reads a tetrahedral mesh file, choosing the format by extension:
// TetGen .node/.ele (either of the pair) or Gmsh .msh (2.2 / 4.1 ASCII).
#include <string>

#include "scene/scene_desc.hpp"

namespace atssim::scene {

// True for the extensions load_tet_mesh reads (.node, .ele, .msh).
bool is_tet_mesh_path(const std::string& path);

// Loads the mesh; vertices that no tetrahedron uses are dropped (Gmsh files
// hold geometry points too), keeping the file's order for the rest. Errors
// about the file as a whole are prefixed with `where` (the scene line that
// names it); errors inside it name the file and line. Throws atssim::Error.
TetMesh load_tet_mesh(const std::string& path, const std::string& where);

}  // namespace atssim::scene
