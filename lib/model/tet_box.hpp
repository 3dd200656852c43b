#pragma once
// A procedural tetrahedral box (scene `box:`).
#include "scene/scene_desc.hpp"

namespace atssim::model {

// A box centred on the origin with (nx+1)(ny+1)(nz+1) vertices; vertex
// (i, j, k) has index (k·(ny+1) + j)·(nx+1) + i. Every cell is split into the
// 6 tets of the Kuhn (Freudenthal) subdivision: the paths from its corner
// (0,0,0) to (1,1,1) along the three axes in each order. Every cell is split
// the same way, so the faces of neighbouring cells match (a conforming mesh),
// and every tet is positively oriented.
scene::TetMesh make_tet_box(const scene::TetBoxDesc& box);

}  // namespace atssim::model
