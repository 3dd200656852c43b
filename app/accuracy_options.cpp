// The accuracy flags that `run` and `schedule` share (docs/accuracy.md,
// "Accuracy as the input").
#include <cmath>

#include <fmt/format.h>
#include <CLI/CLI.hpp>

#include "app/commands.hpp"
#include "util/error.hpp"

namespace atssim::app {

void add_accuracy_options(CLI::App& cmd, double& tolerance, double& budget_ms, std::vector<std::string>& methods) {
  cmd.add_option("--tolerance", tolerance,
                 "Relative energy error per substep wanted, 0 < Y < 1: atssim chooses the cheapest method, iterations "
                 "and schedule that reach it (solver.tolerance)");
  cmd.add_option("--budget", budget_ms,
                 "Wall time per frame allowed (ms): atssim chooses the most accurate choice that fits "
                 "(solver.budget_ms)");
  cmd.add_option("--methods", methods,
                 "With --tolerance or --budget: the methods to choose from, comma separated (default: every "
                 "iterative method the scene allows; solver.methods)")
      ->delimiter(',');
}

void push_accuracy_overrides(const CLI::App& cmd, double tolerance, double budget_ms,
                             const std::vector<std::string>& methods, std::vector<std::string>& overrides) {
  if (cmd.count("--tolerance") > 0) {
    if (!(tolerance > 0.0 && tolerance < 1.0)) {
      throw input_error(fmt::format(
          "--tolerance {}: give the relative energy error wanted per substep, 0 < Y < 1 (e.g. 1e-2)", tolerance));
    }
    overrides.push_back(fmt::format("solver.tolerance={:.17g}", tolerance));
  }
  if (cmd.count("--budget") > 0) {
    if (!(budget_ms > 0.0 && std::isfinite(budget_ms))) {
      throw input_error(
          fmt::format("--budget {}: give the wall time allowed per frame in ms, > 0 (e.g. 20)", budget_ms));
    }
    overrides.push_back(fmt::format("solver.budget_ms={:.17g}", budget_ms));
  }
  if (cmd.count("--methods") > 0) {
    for (const std::string& m : methods) {
      if (m.empty()) throw input_error("--methods: a method name is empty; list them as atssim methods names them");
    }
    overrides.push_back(fmt::format("solver.methods=[{}]", fmt::join(methods, ", ")));
  }
}

}  // namespace atssim::app
