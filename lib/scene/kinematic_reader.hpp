#pragma once
// The motion keys of a collider (velocity, angular_velocity, keyframes) ->
// ColliderMotion, and back to resolved YAML.
#include <array>
#include <string_view>

#include <yaml-cpp/yaml.h>

#include "scene/collider_motion.hpp"
#include "scene/yaml_reader.hpp"

namespace atssim::scene {

inline constexpr std::array<std::string_view, 3> kMotionKeys{"velocity", "angular_velocity", "keyframes"};

// Reads the motion keys of collider map `r` (none: still); throws
// atssim::Error (input) naming the line and the fix.
ColliderMotion read_motion(const YamlReader& r);

// The motion's keys (nothing for a still collider).
void emit_motion(YAML::Emitter& out, const ColliderMotion& m);

}  // namespace atssim::scene
