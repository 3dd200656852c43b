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

// Same, from text; `source_name` is used in messages and `base_dir` resolves
// relative mesh paths.
SceneDesc parse_scene(const std::string& yaml_text, const std::string& source_name, const std::string& base_dir,
                      std::span<const std::string> overrides = {});

}  // namespace atssim::scene
