#pragma once
// What a simulation method tells the rest of atssim about itself: its name,
// the program its plans run, its task kinds, how its iterations run, the
// options it reads under `solver:`, what it can simulate, and how it builds
// a substep plan. Each method folder (lib/solver/<method>/) defines one
// MethodDescription, <method>::kDescription in <method>_method.cpp; the
// registry (method_registry.cpp) lists them, one line each. The pipeline,
// the commands and the "every method" tests ask the registry
// (solver::methods()) by capability instead of naming methods.
#include <map>
#include <set>
#include <span>
#include <string>
#include <string_view>

#include "plan/substep_plan.hpp"
#include "plan/task_kind.hpp"
#include "scene/scene_desc.hpp"
#include "solver/layout/sim_layout.hpp"

namespace atssim::solver {

// A number under `solver:` that a method reads, e.g. solver.chebyshev_rho.
struct MethodOption {
  std::string_view key;
  double default_value = 0.0;
  double min = 0.0, max = 0.0;  // the accepted range
  bool min_open = false;        // min itself excluded
  bool max_open = false;        // max itself excluded
  std::string_view meaning;     // for messages: "a step length 0 < step ≤ 1"
  // A named option (e.g. solver.integrator: rk4): the value is one of these
  // names and its index is the number the method reads; empty = a number.
  std::span<const std::string_view> choices{};
  // The method picks the value from the scene when the scene does not set
  // it (default_value is the usual pick): the resolved scene then leaves
  // the option out, so that running it again picks the same.
  bool depends_on_scene = false;
  // A named option whose choices from this index on make a plan for one
  // device: a schedule other than single is refused at the option's line
  // (app/scene_checks). -1: every choice runs on any schedule.
  int one_device_from = -1;

  // The default as a scene would write it (a name for a named option).
  std::string default_text() const;
};

// The substep and the values of the method's options (defaults filled in).
struct MethodSettings {
  double substep_dt = 1.0 / 960.0;
  int iterations = 8;
  int substeps = 16;  // per frame (for messages that say how many a scene needs)
  std::map<std::string, double, std::less<>> options;
  std::set<std::string, std::less<>> given;  // the options the scene sets

  // The value of one of the method's options; throws atssim::Error
  // (internal) for a key the method does not declare.
  double option(std::string_view key) const;
  // The scene's value, or `fallback` where the scene leaves the option to
  // the method (a default that depends on the scene).
  double option_or(std::string_view key, double fallback) const;
};

struct MethodDescription {
  std::string_view name;     // solver.method
  std::string_view summary;  // one line for `atssim methods` and docs
  // The embedded program its plans run (SubstepPlan::program): the file
  // kernels/<program>/<program>.cl, which the build finds.
  std::string_view program;
  // The task kinds of its own that its plans use, besides the shared ones
  // (plan::TaskKind::predict, …); declared in its folder.
  std::span<const plan::TaskKind> kinds{};
  // Gauss-Seidel iterations (async Gauss-Seidel relaxes them), or Jacobi
  // sweeps that already run on every device with one synchronisation each.
  bool gauss_seidel = false;
  // Each substep is a backward Euler step: its iterations approach the
  // minimiser of the incremental potential (solver/energy). False: it
  // integrates the forces explicitly, and needs a stable step.
  bool implicit = true;
  // Each of its iterations lowers the incremental potential (a descent
  // method): `converge` measures how close it comes to the Newton minimiser.
  bool descent = false;
  std::span<const MethodOption> options{};
  std::span<const scene::SolidModel> solid_models{};  // the tetrahedral models it simulates
  plan::SubstepPlan (*build)(const SimLayout& layout, const MethodSettings& settings) = nullptr;
  // Whether its plan keeps particles out of the scene's colliders (contact
  // and friction tasks); a scene with colliders is refused otherwise.
  bool colliders = true;

  bool simulates(scene::SolidModel model) const;
};

}  // namespace atssim::solver
