#pragma once
// Reads TetGen's .node/.ele pair (TetGen manual §5.2.1 and §5.2.4). Only the
// format is read; the TetGen library (AGPL) is not used.
#include <string>

#include "scene/scene_desc.hpp"

namespace atssim::scene {

// Reads the points of `node_path` and the tetrahedra of `ele_path`. The first
// point's number sets the base (0 or 1) that every index uses; attributes and
// boundary markers are skipped; of 10-node (second-order) tetrahedra the four
// corners are kept. Throws atssim::Error (input) naming the file and line.
TetMesh read_tetgen(const std::string& node_path, const std::string& ele_path);

}  // namespace atssim::scene
