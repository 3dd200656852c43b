#pragma once
// Every method this build knows, and what the pipeline asks of them. Adding
// a method is one folder under lib/solver/, its program under kernels/, and
// one line in method_registry.cpp (docs/architecture.md shows such a change).
#include <span>
#include <string>
#include <string_view>

#include "scene/scene_desc.hpp"
#include "solver/method.hpp"

namespace atssim::solver {

std::span<const MethodDescription* const> methods();

// The method of that name, or nullptr.
const MethodDescription* find_method(std::string_view name);
// The method of that name; an unknown name is an input error naming the
// line that chose it (`where`, "" for a command-line flag) and the methods.
const MethodDescription& method(std::string_view name, std::string_view where = "");

// Checks what a scene asks of `method`: every key under `solver:` that is no
// schedule key names an option of some method (a typo gets "did you mean"),
// the options `method` reads hold numbers in range, and every solid's
// material model is one the method simulates. Input errors name the line.
void check_scene(const scene::SceneDesc& scene, const MethodDescription& method);

// The settings `method` runs the scene with: its substep, iterations and
// options (the scene's values, else the defaults). Calls check_scene.
MethodSettings method_settings(const scene::SceneDesc& scene, const MethodDescription& method);

// The scene's plan: model -> layout -> the method's plan builder.
plan::SubstepPlan build_plan(const scene::SceneDesc& scene, const MethodDescription& method);

// The names of the methods for which `capable` holds (all when null), in
// registry order, comma separated: for help texts and messages.
std::string method_names(bool (*capable)(const MethodDescription&) = nullptr);

}  // namespace atssim::solver
