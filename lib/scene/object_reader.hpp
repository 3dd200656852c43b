#pragma once
// One entry of the scene's objects: list -> ObjectDesc (docs/scene-format.md):
// its type (cloth or solid), shape (grid, box or mesh file), transform,
// material and pins.
#include <filesystem>

#include "scene/scene_desc.hpp"
#include "scene/yaml_reader.hpp"

namespace atssim::scene {

// Reads and validates object `index`; mesh files (relative to `base_dir`)
// are loaded here. Throws atssim::Error (input) naming the scene line.
ObjectDesc read_object(const YamlReader& r, int index, const std::filesystem::path& base_dir);

}  // namespace atssim::scene
