#pragma once
// What every scene object does the same way, cloth or solid: place its
// vertices by the transform, find its pinned vertices, and append its
// particles (lumped mass, inverse mass 0 when pinned) to the model.
#include <string>
#include <vector>

#include "model/model.hpp"
#include "scene/scene_desc.hpp"

namespace atssim::model {

// The range of an object about to be appended to `model`: name, offset
// (the current particle count), vertex count and world-space rest positions.
ObjectRange begin_object(const Model& model, const scene::ObjectDesc& obj,
                         const std::vector<std::array<double, 3>>& vertices);

// Object-local vertices to world space: scale, rotate about x, y, z (degrees), translate.
std::vector<Vec3> place_vertices(const scene::TransformDesc& transform,
                                 const std::vector<std::array<double, 3>>& vertices);

// Throws atssim::Error (input) naming the object's scene line when a placed
// vertex is not finite or further than 1e8 m from the origin (float32
// positions lose all precision beyond).
void check_placed(const scene::ObjectDesc& obj, const std::vector<Vec3>& placed, const std::string& scene_file);

// 1 for each vertex the object's pins name (by index or world-space box).
// Throws atssim::Error (input) naming the object's scene line for an index
// out of range or a box that holds no vertex.
std::vector<char> pinned_flags(const scene::ObjectDesc& obj, const std::vector<Vec3>& rest_position,
                               const std::string& scene_file);

// Appends range.rest_position as particles with the given lumped masses;
// pinned or massless particles get inverse mass 0. Fills range.pinned.
void append_particles(Model& model, ObjectRange& range, const std::vector<double>& mass,
                      const std::vector<char>& pinned);

}  // namespace atssim::model
