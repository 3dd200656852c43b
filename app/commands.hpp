#pragma once
// One function per subcommand (app/cmd_*.cpp); each registers its options
// on the CLI11 app and returns the action to run after parsing.
#include <functional>
#include <string>

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

}  // namespace atssim::app
