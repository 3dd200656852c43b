#pragma once
// One function per subcommand (app/cmd_*.cpp); each registers its options
// on the CLI11 app and returns the action to run after parsing.
#include <functional>
#include <string>
#include <vector>

namespace CLI {
class App;
}

namespace atssim::app {

using Action = std::function<int()>;

Action add_run_command(CLI::App& cli, const std::string& command_line);
Action add_devices_command(CLI::App& cli);
Action add_schedule_command(CLI::App& cli);
Action add_converge_command(CLI::App& cli, const std::string& command_line);
Action add_inspect_command(CLI::App& cli);
Action add_methods_command(CLI::App& cli);

// --tolerance, --budget and --methods (run and schedule), and the scene
// overrides they become (solver.tolerance, solver.budget_ms,
// solver.methods); a value out of range is an input error naming the flag.
void add_accuracy_options(CLI::App& cmd, double& tolerance, double& budget_ms, std::vector<std::string>& methods);
void push_accuracy_overrides(const CLI::App& cmd, double tolerance, double budget_ms,
                             const std::vector<std::string>& methods, std::vector<std::string>& overrides);

}  // namespace atssim::app
