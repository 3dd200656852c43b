#pragma once
// The scene's `contact:` map -> SelfContactDesc, and back to resolved YAML
// (docs/scene-format.md, "contact").
#include <yaml-cpp/yaml.h>

#include "scene/contact_desc.hpp"
#include "scene/yaml_reader.hpp"

namespace atssim::scene {

// Reads and validates `contact:`; throws atssim::Error (input) naming the
// scene line and the fix.
SelfContactDesc read_self_contact(const YamlReader& r);

// As resolved YAML (every key, defaults filled in); nothing when off.
void emit_self_contact(YAML::Emitter& out, const SelfContactDesc& c);

}  // namespace atssim::scene
