#pragma once
// Builds the Model of a scene: meshes (grid or file) placed by their
// transforms, lumped masses from density × area, pins, and the element sets
// the materials ask for.
#include <array>
#include <vector>

#include "model/model.hpp"
#include "scene/scene_desc.hpp"

namespace atssim::model {

// A regular grid in the local xz plane, centred on the origin; vertex (i, k)
// has index k * nx + i. Each quad is split along one diagonal.
scene::TriangleMesh make_grid_mesh(const scene::GridDesc& grid);

// Unique undirected edges of a triangle mesh, each as (min, max), sorted.
std::vector<std::array<int, 2>> unique_edges(const std::vector<std::array<int, 3>>& triangles);

// Interior edges with their two opposite vertices: {v0, v1, v2, v3}.
std::vector<std::array<int, 4>> bending_stencils(const std::vector<std::array<int, 3>>& triangles);

// Throws atssim::Error (input) naming the scene line when e.g. a pinned
// vertex index is out of range.
Model build_model(const scene::SceneDesc& scene);

}  // namespace atssim::model
