#include "scene/scene_loader.hpp"

#include <algorithm>
#include <array>
#include <filesystem>
#include <fstream>
#include <optional>
#include <sstream>

#include <fmt/format.h>
#include <yaml-cpp/yaml.h>

#include "scene/accuracy_reader.hpp"
#include "scene/collider_reader.hpp"
#include "scene/contact_reader.hpp"
#include "scene/input_file.hpp"
#include "scene/object_reader.hpp"
#include "scene/scene_yaml.hpp"
#include "scene/yaml_document.hpp"
#include "scene/yaml_keys.hpp"
#include "scene/yaml_reader.hpp"
#include "util/error.hpp"

namespace atssim::scene {

namespace {

namespace fs = std::filesystem;

constexpr std::array<std::string_view, 8> kRootKeys{"simulation", "objects", "solver",    "output",
                                                    "devices",    "memory",  "colliders", "contact"};
constexpr std::array<std::string_view, 9> kSimulationKeys{
    "fps", "dt", "substeps", "iterations", "frames", "gravity", "ground", "air_drag", "energy_growth_limit"};
// Keys under solver: that configure how the devices run a substep; every
// other key is an option of a method (MethodOptionDesc).
constexpr std::array<std::string_view, 13> kScheduleKeys{
    "method",       "schedule",     "async_depth", "merge",     "async_fetch", "replay", "executor",
    "wait_timeout", "task_merging", "tolerance",   "budget_ms", "recheck",     "methods"};
constexpr std::array<std::string_view, 3> kExecutors{"auto", "fused", "events"};
constexpr std::array<std::string_view, 4> kSchedules{"single", "split", "heft", "async"};
constexpr std::array<std::string_view, 3> kMerges{"average_displacements", "average_positions", "main_precedence"};
constexpr std::array<std::string_view, 2> kOutputKeys{"path", "stride"};

// A list index: decimal digits only ("0x1", "1e2" or "0\x01" are none), below 2^31.
std::optional<std::size_t> list_index(const std::string& key) {
  if (key.empty() || key.size() > 9) return std::nullopt;
  std::size_t index = 0;
  for (char c : key) {
    if (c < '0' || c > '9') return std::nullopt;
    index = index * 10 + static_cast<std::size_t>(c - '0');
  }
  return index;
}

// The first `count` keys of an override path, joined with dots.
std::string joined(const std::vector<std::string>& keys, std::size_t count) {
  if (count == 0) return "the scene's top level";
  std::string out;
  for (std::size_t k = 0; k < count; ++k) out += (k ? "." : "") + keys[k];
  return out;
}

// Applies "a.b.0.c=value": walks (creating maps as needed) and replaces the
// leaf with the value parsed as YAML.
void apply_override(YAML::Node& root, const std::string& assignment, const std::string& source,
                    std::map<std::string, std::string>& applied) {
  const auto eq = assignment.find('=');
  if (eq == std::string::npos || eq == 0) {
    throw input_error(fmt::format("--set {}: expected key=value, e.g. --set simulation.substeps=32", assignment));
  }
  const std::string path = assignment.substr(0, eq);
  YAML::Node value;
  try {
    value = YAML::Load(assignment.substr(eq + 1));
  } catch (const YAML::Exception& e) {
    throw input_error(fmt::format("--set {}: value is not valid YAML ({}); quote text values", assignment, e.msg));
  }
  check_yaml_value(value, "--set " + assignment);
  std::vector<std::string> keys;
  std::stringstream ss(path);
  for (std::string k; std::getline(ss, k, '.');) {
    if (k.empty()) throw input_error(fmt::format("--set {}: empty key in '{}'", assignment, path));
    keys.push_back(k);
  }
  // yaml-cpp nodes are handles: walk with reset() copies, assign at the leaf.
  std::vector<YAML::Node> chain{root};
  for (std::size_t i = 0; i + 1 < keys.size(); ++i) {
    YAML::Node parent = chain.back();
    YAML::Node next;
    if (parent.IsScalar()) {
      throw input_error(fmt::format("--set {}: '{}' is a value, not a map: it has no key '{}'", assignment,
                                    joined(keys, i), keys[i]));
    }
    if (parent.IsSequence()) {
      const std::size_t index = list_index(keys[i]).value_or(parent.size());
      if (index >= parent.size()) {
        throw input_error(fmt::format("--set {}: '{}' is a list of {} items; use an index from 0 to {}", assignment,
                                      keys[i - (i > 0 ? 1 : 0)], parent.size(),
                                      parent.size() == 0 ? 0 : parent.size() - 1));
      }
      next = parent[index];
    } else {
      next = parent[keys[i]];
      if (!next || next.IsNull() || next.IsScalar()) {
        parent[keys[i]] = YAML::Node(YAML::NodeType::Map);
        next = parent[keys[i]];
      }
    }
    chain.push_back(next);
  }
  YAML::Node leaf_parent = chain.back();
  if (leaf_parent.IsScalar()) {
    throw input_error(fmt::format("--set {}: '{}' is a value, not a map: it has no key '{}'", assignment,
                                  joined(keys, keys.size() - 1), keys.back()));
  }
  if (leaf_parent.IsSequence()) {
    const std::optional<std::size_t> found = list_index(keys.back());
    if (!found) throw input_error(fmt::format("--set {}: '{}' is not a list index", assignment, keys.back()));
    const std::size_t index = *found;
    if (index >= leaf_parent.size()) {
      throw input_error(fmt::format("--set {}: index {} is past the end of the list", assignment, index));
    }
    leaf_parent[index] = value;
  } else {
    leaf_parent[keys.back()] = value;
  }
  applied[path] = assignment;
  (void)source;
}

SimulationDesc read_simulation(const YamlReader& r) {
  SimulationDesc sim;
  if (r.is_null()) return sim;
  r.expect_map(kSimulationKeys);
  if (r.has("fps") && r.has("dt")) {
    r.child("dt").fail("both 'fps' and 'dt' are given", "keep one of them (dt = 1/fps)");
  }
  if (r.has("fps")) {
    sim.frame_dt = 1.0 / r.child("fps").number_in(0.1, 1e6, false, "frames per second from 0.1 to 1e6 (dt ≤ 10 s)");
  }
  if (r.has("dt")) sim.frame_dt = r.child("dt").number_in(0.0, 10.0, true, "a frame time in seconds, 0 < dt ≤ 10");
  if (r.has("substeps")) sim.substeps = r.child("substeps").integer_in(1, 10000);
  if (r.has("iterations")) sim.iterations = r.child("iterations").integer_in(1, 100000);
  if (r.has("frames")) sim.frames = r.child("frames").integer_in(1, 10000000);
  if (r.has("ground")) sim.ground = r.child("ground").number_in(-1e6, 1e6, false, "a ground height in metres");
  if (r.has("air_drag")) {
    sim.air_drag = r.child("air_drag").number_in(0.0, 1e6, false, "a drag rate in 1/s ≥ 0 (force −m·c·v)");
  }
  if (r.has("energy_growth_limit")) {
    const YamlReader limit = r.child("energy_growth_limit");
    const double v = limit.number();
    if (v != 0.0 && !(v > 1.0 && v <= 1e30)) {
      limit.fail(fmt::format("'simulation.energy_growth_limit' is {}, out of range", limit.node().Scalar()),
                 "use a factor above 1 (default 1000), or 0 to turn the energy check off");
    }
    sim.energy_growth_limit = v;
  }
  if (r.has("gravity")) {
    sim.gravity = r.child("gravity").vec3();
    for (double g : sim.gravity) {
      if (std::abs(g) > 1e6) r.child("gravity").fail("gravity is implausibly large", "use m/s², e.g. [0, -9.81, 0]");
    }
  }
  return sim;
}

}  // namespace

SceneDesc parse_scene(const std::string& yaml_text, const std::string& source_name, const std::string& base_dir,
                      std::span<const std::string> overrides) {
  YamlSource source{source_name, {}};
  YAML::Node root;
  try {
    // The one document: a second one ('---') is refused, not ignored.
    root = load_one_document(yaml_text, source_name);
  } catch (const YAML::ParserException& e) {
    throw input_error(fmt::format("{}:{}: YAML syntax error: {}; fix the indentation or quoting there", source_name,
                                  e.mark.line + 1, e.msg));
  }
  if (!root || root.IsNull()) root = YAML::Node(YAML::NodeType::Map);
  check_yaml_keys(root, source_name);
  for (const std::string& assignment : overrides) {
    try {
      apply_override(root, assignment, source_name, source.overrides);
    } catch (const YAML::Exception& e) {  // a walk the checks above did not foresee: still the --set's fault
      throw input_error(fmt::format("--set {}: cannot apply it to this scene ({})", assignment, e.msg));
    }
  }

  const YamlReader top(root, "", &source);
  top.expect_map(kRootKeys);

  SceneDesc scene;
  scene.source_path = source_name;
  scene.yaml_text = yaml_text;
  scene.simulation = read_simulation(top.child("simulation"));

  if (!top.has("objects")) {
    top.fail("the scene has no 'objects'", "add an objects: list with at least one cloth");
  }
  const auto objects = top.child("objects").sequence();
  if (objects.empty()) top.child("objects").fail("'objects' is empty", "add at least one object");
  std::map<std::string, int> names;  // name -> line
  for (std::size_t i = 0; i < objects.size(); ++i) {
    scene.objects.push_back(read_object(objects[i], static_cast<int>(i), fs::path(base_dir)));
    const ObjectDesc& obj = scene.objects.back();
    if (const auto it = names.find(obj.name); it != names.end()) {
      const YamlReader at = objects[i].has("name") ? objects[i].child("name") : objects[i];
      at.fail(fmt::format("two objects are named '{}' (the first on line {})", obj.name, it->second),
              "give every object its own name");
    }
    names.emplace(obj.name, obj.source_line);
  }

  if (top.has("colliders")) {
    const auto colliders = top.child("colliders").sequence();
    for (std::size_t i = 0; i < colliders.size(); ++i) {
      scene.colliders.push_back(read_collider(colliders[i], static_cast<int>(i), fs::path(base_dir)));
    }
  }

  if (top.has("contact")) scene.contact = read_self_contact(top.child("contact"));

  const YamlReader solver = top.child("solver");
  if (!solver.is_null()) {
    for (const std::string& key : solver.map_keys()) {
      if (std::find(kScheduleKeys.begin(), kScheduleKeys.end(), key) != kScheduleKeys.end()) continue;
      const YamlReader option = solver.child(key);
      scene.solver.method_options.push_back({key, option.string(), option.where()});
    }
    scene.solver.accuracy = read_accuracy(solver);
    if (solver.has("method")) {
      const YamlReader m = solver.child("method");
      scene.solver.method = m.string();
      scene.solver.method_where = m.where();
    }
    if (solver.has("schedule")) {
      const YamlReader m = solver.child("schedule");
      scene.solver.schedule = m.string();
      scene.solver.schedule_where = m.where();
      bool known = false;
      for (auto k : kSchedules) known = known || scene.solver.schedule == k;
      if (!known) {
        m.fail(fmt::format("unknown schedule '{}'", scene.solver.schedule),
               "use single (one device), split (every color block divided by device speed), heft or async");
      }
    }
    if (solver.has("async_depth")) scene.solver.async_depth = solver.child("async_depth").integer_in(1, 64);
    if (solver.has("merge")) {
      const YamlReader m = solver.child("merge");
      scene.solver.merge = m.string();
      bool known = false;
      for (auto k : kMerges) known = known || scene.solver.merge == k;
      if (!known) {
        m.fail(fmt::format("unknown merge strategy '{}'", scene.solver.merge),
               "use average_displacements, average_positions or main_precedence");
      }
    }
    if (solver.has("async_fetch")) {
      const YamlReader m = solver.child("async_fetch");
      const std::string fetch = m.string();
      if (fetch != "latest" && fetch != "dependencies") {
        m.fail(fmt::format("unknown async_fetch '{}'", fetch),
               "use latest (merge the newest finished result) or dependencies (only what the graph requires)");
      }
      scene.solver.async_latest = fetch == "latest";
    }
    if (solver.has("task_merging")) {
      const YamlReader m = solver.child("task_merging");
      const std::string v = m.string();
      if (v != "auto" && v != "off") {
        m.fail(fmt::format("unknown task_merging '{}'", v),
               "use auto (heft merges colour blocks where that is predicted to end the substep sooner) or off");
      }
      scene.solver.task_merging = v == "auto";
    }
    if (solver.has("executor")) {
      const YamlReader m = solver.child("executor");
      scene.solver.executor = m.string();
      bool known = false;
      for (auto k : kExecutors) known = known || scene.solver.executor == k;
      if (!known) {
        m.fail(fmt::format("unknown executor '{}'", scene.solver.executor),
               "use auto (fused where every device has fine-grain SVM with atomics), fused (one launch per device "
               "and frame) or events (one launch per task)");
      }
    }
    if (solver.has("wait_timeout")) {
      scene.solver.wait_timeout_s =
          solver.child("wait_timeout").number_in(0.0, 3600.0, true, "seconds, 0 < wait_timeout ≤ 3600");
    }
    if (solver.has("replay")) {
      const YamlReader m = solver.child("replay");
      const std::string v = m.string();
      if (v != "true" && v != "false") m.fail(fmt::format("'replay' is '{}'", v), "use true or false");
      scene.solver.replay = v == "true";
    }
  }
  const YamlReader output = top.child("output");
  if (!output.is_null()) {
    output.expect_map(kOutputKeys);
    if (output.has("path")) {
      scene.output.path = output.child("path").string();
      if (scene.output.path.empty())
        output.child("path").fail("'output.path' is empty", "give a file name such as run.h5");
    }
    if (output.has("stride")) scene.output.stride = output.child("stride").integer_in(1, 1000000);
  }
  if (top.has("devices")) {
    const YamlReader d = top.child("devices");
    scene.devices = d.string();
    scene.devices_where = d.where();
    if (scene.devices.empty())
      d.fail("'devices' is empty", "give a device spec such as cpu, 0 or cpu/2 (see atssim devices)");
  }
  if (top.has("memory")) {
    const YamlReader m = top.child("memory");
    scene.memory = m.string();
    if (scene.memory != "shared" && scene.memory != "separate") {
      m.fail(fmt::format("unknown memory '{}'", scene.memory),
             "use shared (the devices of one platform share SVM) or separate (every device its own memory, copies "
             "through the host)");
    }
  }

  scene.resolved_yaml = to_resolved_yaml(scene);
  return scene;
}

SceneDesc load_scene_file(const std::string& path, std::span<const std::string> overrides) {
  check_input_file(path, "scene file", "", kMaxSceneBytes);
  std::ifstream in(path);
  if (!in) throw input_error(fmt::format("{}: scene file cannot be read; check its permissions", path));
  std::stringstream text;
  text << in.rdbuf();
  const fs::path base = fs::absolute(fs::path(path)).parent_path();
  return parse_scene(text.str(), path, base.string(), overrides);
}

}  // namespace atssim::scene
