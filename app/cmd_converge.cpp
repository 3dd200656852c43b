// `atssim converge SCENE`: relative energy error per iteration count and its
// cost in time, per schedule, against a Newton reference.
#include <fmt/format.h>
#include <CLI/CLI.hpp>

#include "app/commands.hpp"
#include "app/convergence.hpp"
#include "solver/method_registry.hpp"
#include "util/error.hpp"

namespace atssim::app {

Action add_converge_command(CLI::App& cli, const std::string& command_line) {
  auto o = std::make_shared<ConvergeOptions>();
  auto output = std::make_shared<std::string>("convergence.h5");
  auto devices = std::make_shared<std::string>();
  auto memory = std::make_shared<std::string>();
  auto method = std::make_shared<std::string>();
  CLI::App* cmd = cli.add_subcommand(
      "converge", "Speed/accuracy: relative energy error per iteration vs a Newton reference, per schedule");
  cmd->add_option("scene", o->scene_path, "Scene file (YAML)")->required();
  cmd->add_option("-o,--output", *output, "Output HDF5 file (/convergence)")->capture_default_str();
  cmd->add_option("--methods", o->methods, "Solvers to compare: " + solver::method_names() + " (comma separated)")
      ->delimiter(',');
  cmd->add_option("--schedules", o->schedules, "single, split, heft, async (comma separated)")->delimiter(',');
  cmd->add_option("--merges", o->merges,
                  "Merge strategies for async: average_displacements, average_positions, main_precedence")
      ->delimiter(',');
  cmd->add_option("--iterations", o->max_iterations, "Largest iteration count (k = 1, 2, 4, …, N)")
      ->capture_default_str();
  cmd->add_option("--frames-before", o->frames_before, "Frames simulated first to reach a moving state")
      ->capture_default_str();
  cmd->add_option("--from", o->from,
                  "A result file of atssim run of this scene: measure from the state of its last written frame "
                  "instead of --frames-before");
  cmd->add_option("--devices", *devices, "Device spec (two-device schedules need two, e.g. cpu/2)");
  cmd->add_option("--memory", *memory,
                  "shared (a platform's devices share SVM) or separate (every device its own memory, copies "
                  "through the host)")
      ->check(CLI::IsMember({"shared", "separate"}));
  cmd->add_option("--set", o->overrides, "Override a scene key (repeatable)");
  cmd->add_option("--method", *method, "Solver method of the scene (solver.method); --methods chooses those compared");
  return [o, output, devices, memory, method, command_line, cmd]() {
    ConvergeOptions options = *o;
    options.command_line = command_line;
    if (cmd->count("--output") > 0 && output->empty()) throw input_error("-o/--output: the output path is empty");
    if (cmd->count("--devices") > 0 && devices->empty()) throw input_error("--devices: the device spec is empty");
    if (cmd->count("--method") > 0 && method->empty()) throw input_error("--method: the method is empty");
    if (cmd->count("--from") > 0 && options.from.empty()) throw input_error("--from: the file name is empty");
    if (!method->empty()) options.overrides.push_back("solver.method=" + *method);
    if (!devices->empty()) options.overrides.push_back("devices=" + *devices);
    if (!memory->empty()) options.overrides.push_back("memory=" + *memory);
    const io::ConvergenceResult result = run_convergence(options);
    io::write_convergence(*output, result);
    fmt::print("{}wrote {}\n", format_convergence_table(result), *output);
    return 0;
  };
}

}  // namespace atssim::app
