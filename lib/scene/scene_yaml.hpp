#pragma once
// The resolved scene as YAML: every value after defaults and --set, in the
// scene format, so /scene/resolved in the output reruns the same simulation.
#include <string>

#include "scene/scene_desc.hpp"

namespace atssim::scene {

std::string to_resolved_yaml(const SceneDesc& scene);

}  // namespace atssim::scene
