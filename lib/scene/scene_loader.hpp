#pragma once
// YAML scene (format v1, docs/scene-format.md) -> validated SceneDesc.
#include <span>
#include <string>

#include "scene/scene_desc.hpp"

namespace atssim::scene {

// Reads and validates a scene file. `overrides` are "dotted.path=value"
// strings from --set; each replaces (or adds) one key before validation.
// Mesh files are loaded here. Throws atssim::Error (input) on any problem.
SceneDesc load_scene_file(const std::string& path, std::span<const std::string> overrides = {});

// Throws atssim::Error (input), naming the line that chose it, when `method`
// cannot simulate an object of the scene: solids with model springs (none
// can yet), neo-Hookean solids under xpbd (StVK strain constraints only).
void check_method_support(const SceneDesc& scene, const std::string& method);

// Same, from text; `source_name` is used in messages and `base_dir` resolves
// relative mesh paths.
SceneDesc parse_scene(const std::string& yaml_text, const std::string& source_name,
                      const std::string& base_dir, std::span<const std::string> overrides = {});

}  // namespace atssim::scene
