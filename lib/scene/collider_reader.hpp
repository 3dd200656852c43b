#pragma once
// One entry of the scene's colliders: list -> ColliderDesc, and back to
// resolved YAML (docs/scene-format.md, "colliders").
#include <filesystem>

#include <yaml-cpp/yaml.h>

#include "scene/collider_desc.hpp"
#include "scene/yaml_reader.hpp"

namespace atssim::scene {

// Reads and validates collider `index` (a mesh's file is relative to
// `base_dir`); throws atssim::Error (input) naming the scene line and the fix.
ColliderDesc read_collider(const YamlReader& r, int index, const std::filesystem::path& base_dir = {});

// The collider as resolved YAML (every key, defaults filled in).
void emit_collider(YAML::Emitter& out, const ColliderDesc& c);

}  // namespace atssim::scene
