#include "solver/method_registry.hpp"

#include <cmath>
#include <string>
#include <vector>

#include <fmt/format.h>

#include "model/cloth_builder.hpp"
#include "util/did_you_mean.hpp"
#include "util/error.hpp"

// Every method, one line each, in the order `atssim methods` lists them:
// M(ns) names the description its folder defines as
// atssim::solver::ns::kDescription (lib/solver/<method>/<method>_method.cpp).
// clang-format off
#define ATSSIM_EACH_METHOD(M) \
  M(xpbd)                     \
  M(vbd)                      \
  M(sosd)                     \
  M(jpgd)                     \
  M(explicit_rk)              \
  /* a new method: one line above this one */
// clang-format on

namespace atssim::solver {

#define ATSSIM_DECLARE_METHOD(ns)              \
  namespace ns {                               \
  extern const MethodDescription kDescription; \
  }
ATSSIM_EACH_METHOD(ATSSIM_DECLARE_METHOD)
#undef ATSSIM_DECLARE_METHOD

namespace {

#define ATSSIM_METHOD_ENTRY(ns) &ns::kDescription,
const MethodDescription* const kMethods[] = {ATSSIM_EACH_METHOD(ATSSIM_METHOD_ENTRY)};
#undef ATSSIM_METHOD_ENTRY

const MethodOption* find_option(const MethodDescription& m, std::string_view key) {
  for (const MethodOption& o : m.options) {
    if (o.key == key) return &o;
  }
  return nullptr;
}

// The value of a scene option of `method`, checked against its range.
double option_value(const scene::MethodOptionDesc& given, const MethodOption& option) {
  if (!option.choices.empty()) {
    for (std::size_t i = 0; i < option.choices.size(); ++i) {
      if (option.choices[i] == given.value) return static_cast<double>(i);
    }
    const std::string guess = closest_match(given.value, option.choices);
    throw input_error(fmt::format("{}: solver.{} is '{}'; use {}{}", given.where, given.key, given.value,
                                  option.meaning, guess.empty() ? "" : fmt::format(" (did you mean '{}'?)", guess)));
  }
  double v = 0.0;
  std::size_t used = 0;
  try {
    v = std::stod(given.value, &used);
  } catch (const std::exception&) {
    used = 0;
  }
  const bool number = used > 0 && used == given.value.size() && std::isfinite(v);
  const bool low = option.min_open ? v <= option.min : v < option.min;
  const bool high = option.max_open ? v >= option.max : v > option.max;
  if (!number || low || high) {
    throw input_error(
        fmt::format("{}: solver.{} is '{}'; use {}", given.where, given.key, given.value, option.meaning));
  }
  return v;
}

void check_option_keys(const scene::SceneDesc& scene) {
  std::vector<std::string_view> known;
  for (const MethodDescription* m : kMethods) {
    for (const MethodOption& o : m->options) known.push_back(o.key);
  }
  for (const scene::MethodOptionDesc& given : scene.solver.method_options) {
    if (std::find(known.begin(), known.end(), given.key) != known.end()) continue;
    const std::string guess = closest_match(given.key, known);
    throw input_error(fmt::format("{}: unknown key 'solver.{}'; {}", given.where, given.key,
                                  guess.empty() ? fmt::format("method options are: {}", fmt::join(known, ", "))
                                                : fmt::format("did you mean '{}'?", guess)));
  }
}

void check_solids(const scene::SceneDesc& scene, const MethodDescription& method) {
  for (const scene::ObjectDesc& o : scene.objects) {
    if (o.type != scene::ObjectType::solid || method.simulates(o.material.solid_model)) continue;
    std::string others;
    for (const MethodDescription* m : kMethods) {
      if (m->simulates(o.material.solid_model)) others += fmt::format("{}{}", others.empty() ? "" : ", ", m->name);
    }
    // Blame the line that chose the model, else the one that chose the
    // method, else the object (both defaults).
    const std::string& model_where = o.material.model_where;
    const std::string where = !model_where.empty() ? model_where
                              : !scene.solver.method_where.empty()
                                  ? scene.solver.method_where
                                  : fmt::format("{}:{}", scene.source_path, o.source_line);
    const std::string_view model = scene::to_string(o.material.solid_model);
    if (others.empty()) {
      throw input_error(
          fmt::format("{}: solid '{}' has model {}, which no solver simulates yet; use neo_hookean or "
                      "stvk",
                      where, o.name, model));
    }
    std::string own;
    for (scene::SolidModel m : method.solid_models)
      own += fmt::format("{}{}", own.empty() ? "" : " or ", scene::to_string(m));
    throw input_error(
        fmt::format("{}: solid '{}' is {}{}, and solver.method {} does not simulate it; set its "
                    "material.model to {}, or use solver.method {}",
                    where, o.name, model, model_where.empty() ? " (the default)" : "", method.name,
                    own.empty() ? "another model" : own, others));
  }
}

}  // namespace

std::span<const MethodDescription* const> methods() { return kMethods; }

const MethodDescription* find_method(std::string_view name) {
  for (const MethodDescription* m : kMethods) {
    if (m->name == name) return m;
  }
  return nullptr;
}

const MethodDescription& method(std::string_view name, std::string_view where) {
  if (const MethodDescription* m = find_method(name)) return *m;
  throw input_error(fmt::format("{}unknown solver method '{}'; available: {}",
                                where.empty() ? "" : fmt::format("{}: ", where), name, method_names()));
}

void check_scene(const scene::SceneDesc& scene, const MethodDescription& method) {
  check_option_keys(scene);
  for (const scene::MethodOptionDesc& given : scene.solver.method_options) {
    if (const MethodOption* o = find_option(method, given.key)) option_value(given, *o);
  }
  check_solids(scene, method);
  if (!method.colliders && (!scene.colliders.empty() || scene.contact.enabled)) {
    const std::string where = !scene.solver.method_where.empty() ? scene.solver.method_where
                              : scene.colliders.empty()
                                  ? scene.contact.where
                                  : fmt::format("{}:{}", scene.source_path, scene.colliders.front().source_line);
    std::string others;
    for (const MethodDescription* m : kMethods) {
      if (m->colliders) others += fmt::format("{}{}", others.empty() ? "" : ", ", m->name);
    }
    throw input_error(
        fmt::format("{}: solver.method {} has no contact with colliders or between objects yet; remove the "
                    "scene's colliders and contact, or use solver.method {}",
                    where, method.name, others));
  }
}

MethodSettings method_settings(const scene::SceneDesc& scene, const MethodDescription& method) {
  check_scene(scene, method);
  MethodSettings s;
  s.substep_dt = scene.simulation.frame_dt / scene.simulation.substeps;
  s.iterations = scene.simulation.iterations;
  s.substeps = scene.simulation.substeps;
  for (const MethodOption& o : method.options) s.options[std::string(o.key)] = o.default_value;
  for (const scene::MethodOptionDesc& given : scene.solver.method_options) {
    if (const MethodOption* o = find_option(method, given.key)) {
      s.options[given.key] = option_value(given, *o);
      s.given.insert(given.key);
    }
  }
  return s;
}

plan::SubstepPlan build_plan(const scene::SceneDesc& scene, const MethodDescription& method) {
  const MethodSettings settings = method_settings(scene, method);
  return method.build(make_sim_layout(model::build_model(scene)), settings);
}

std::string method_names(bool (*capable)(const MethodDescription&)) {
  std::string out;
  for (const MethodDescription* m : kMethods) {
    if (capable == nullptr || capable(*m)) out += fmt::format("{}{}", out.empty() ? "" : ", ", m->name);
  }
  return out;
}

}  // namespace atssim::solver
