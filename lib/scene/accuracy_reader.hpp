#pragma once
// solver.tolerance / budget_ms / recheck / methods -> AccuracyDesc, and back
// to resolved YAML (docs/scene-format.md, "Accuracy as the input").
#include <yaml-cpp/yaml.h>

#include "scene/accuracy_desc.hpp"
#include "scene/yaml_reader.hpp"

namespace atssim::scene {

// Reads those keys of the `solver:` map (absent keys keep the defaults);
// throws atssim::Error (input) naming the scene line and the fix.
AccuracyDesc read_accuracy(const YamlReader& solver);

// The keys that differ from the defaults, into the open solver map.
void emit_accuracy(YAML::Emitter& out, const AccuracyDesc& a);

}  // namespace atssim::scene
