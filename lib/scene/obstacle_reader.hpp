#pragma once
// The keys of a triangle-mesh obstacle (`type: mesh`: file, scale,
// position, rotation) -> ColliderDesc; the mesh is loaded through assimp.
#include <filesystem>

#include <yaml-cpp/yaml.h>

#include "scene/collider_desc.hpp"
#include "scene/yaml_reader.hpp"

namespace atssim::scene {

// Reads the mesh keys of collider map `r` into `c` and loads the file
// (relative to `base_dir`); a missing, unreadable or empty file, or one
// without triangles, throws atssim::Error (input) naming the line.
void read_mesh_obstacle(const YamlReader& r, ColliderDesc& c, const std::filesystem::path& base_dir);

// The mesh keys as resolved YAML.
void emit_mesh_obstacle(YAML::Emitter& out, const ColliderDesc& c);

}  // namespace atssim::scene
