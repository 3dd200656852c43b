#pragma once
// The methods an "every method" test runs: each method of the registry
// (solver::methods()) that takes the test's scene, so that a new method is
// tested by every test whose scene it can run, and no test lists methods.
#include <functional>
#include <set>
#include <string>
#include <vector>

#include "plan/substep_plan.hpp"
#include "plan/task_kind.hpp"
#include "scene/scene_loader.hpp"
#include "solver/method_registry.hpp"
#include "util/error.hpp"

namespace atssim::test {

using Capability = std::function<bool(const solver::MethodDescription&)>;

// The names, in registry order, of the methods for which `capable` holds
// (every method when it is empty) and that take the scene `scene_for(name)`
// (its files under `dir`) with solver.method set to them: the registry's
// checks pass (options, solid models, colliders) and the method's plan
// builder builds it (an explicit method refuses a step above its stable one).
inline std::vector<std::string> methods_taking(const std::function<std::string(const std::string&)>& scene_for,
                                               const Capability& capable = {}, const std::string& dir = ".") {
  std::vector<std::string> out;
  for (const solver::MethodDescription* m : solver::methods()) {
    if (capable && !capable(*m)) continue;
    const std::string name(m->name);
    try {
      const std::vector<std::string> method{"solver.method=" + name};
      const scene::SceneDesc s = scene::parse_scene(scene_for(name), dir + "/scene.yaml", dir, method);
      (void)solver::build_plan(s, *m);
    } catch (const Error& e) {
      if (e.kind() != ErrorKind::input) throw;
      continue;
    }
    out.push_back(name);
  }
  return out;
}

// The same for one scene whatever the method.
inline std::vector<std::string> methods_taking(const std::string& yaml, const Capability& capable = {},
                                               const std::string& dir = ".") {
  return methods_taking([&](const std::string&) { return yaml; }, capable, dir);
}

// Capabilities the tests ask for (solver/method.hpp).
inline bool implicit(const solver::MethodDescription& m) { return m.implicit; }
inline bool descent(const solver::MethodDescription& m) { return m.descent; }

// The names of the methods for which `capable` holds, in registry order.
inline std::vector<std::string> methods_where(const Capability& capable) {
  std::vector<std::string> out;
  for (const solver::MethodDescription* m : solver::methods()) {
    if (capable(*m)) out.emplace_back(m->name);
  }
  return out;
}

// The descent methods: what `converge` compares against the Newton minimiser.
inline std::vector<std::string> descent_methods() { return methods_where(descent); }

// A solid model `method` simulates, as a scene names it: neo_hookean where it
// can, else stvk (XPBD's strain constraints are the StVK energy).
inline std::string solid_model_for(const std::string& method) {
  return solver::method(method).simulates(scene::SolidModel::neo_hookean) ? "neo_hookean" : "stvk";
}

// A corner-pinned cloth of resolution × resolution above the ground beside a
// soft box lying on it: stretch, bending, tetrahedra and the ground task in
// one substep of `method` (the box of a model it simulates: solid_model_for).
inline std::string cloth_and_box_yaml(const std::string& method, int resolution) {
  const std::string solid = solid_model_for(method);
  const std::string r = std::to_string(resolution);
  return "simulation: {fps: 60, substeps: 2, iterations: 4, ground: 0.0}\n"
         "objects:\n"
         "  - name: cloth\n"
         "    grid: {size: [1, 1], resolution: [" +
         r + ", " + r +
         "]}\n"
         "    transform: {translate: [0, 0.3, 0]}\n"
         "    material: {density: 0.2, stretch_stiffness: 1.0e3, bend_stiffness: 1.0e-3}\n"
         "    pins: {boxes: [{min: [-0.51, 0.29, -0.51], max: [-0.49, 0.31, -0.49]}]}\n"
         "  - name: box\n"
         "    type: solid\n"
         "    box: {size: [0.2, 0.2, 0.2], resolution: [2, 2, 2]}\n"
         "    transform: {translate: [0.8, 0.09, 0], rotate: [0, 0, 10]}\n"
         "    material: {density: 1000, youngs_modulus: 5.0e4, poisson_ratio: 0.3, model: " +
         solid +
         "}\n"
         "solver: {method: " +
         method + "}\n";
}

// Every method's name; with `keep`, those it accepts (issue 26's form of
// methods_where).
template <typename Keep>
std::vector<std::string> method_names(Keep keep) {
  std::vector<std::string> names;
  for (const solver::MethodDescription* m : solver::methods()) {
    if (keep(*m)) names.emplace_back(m->name);
  }
  return names;
}
inline std::vector<std::string> method_names() {
  return method_names([](const solver::MethodDescription&) { return true; });
}

// How many kinds of Gauss-Seidel task a plan has: async overlaps the chains
// of different kinds and keeps each kind's order (He et al. 2025 §4.1.2).
inline std::size_t gauss_seidel_kinds(const plan::SubstepPlan& plan) {
  std::set<int> kinds;
  for (const sched::Task& t : plan.graph.tasks()) {
    if (plan::traits(plan::kind_of(t)).gauss_seidel) kinds.insert(t.kind);
  }
  return kinds.size();
}

}  // namespace atssim::test
