// atssim: the command-line front. Parses, runs one subcommand, and turns
// every atssim::Error into one line on stderr and its exit code.
#include <cstdio>
#include <string>

#include <fmt/format.h>
#include <CLI/CLI.hpp>

#include "app/commands.hpp"
#include "io/h5_errors.hpp"
#include "util/error.hpp"
#include "util/freed_memory.hpp"

int main(int argc, char** argv) {
  atssim::io::init_hdf5_for_command_line();
  atssim::util::keep_freed_memory();  // (a refusal only costs speed)
  std::string command_line;
  for (int i = 0; i < argc; ++i) command_line += (i ? " " : "") + std::string(argv[i]);

  CLI::App cli{"atssim — cloth and deformable-body simulation scheduled across OpenCL devices"};
  cli.require_subcommand(1);
  cli.set_version_flag("--version", std::string(ATSSIM_VERSION));
  const atssim::app::Action run = atssim::app::add_run_command(cli, command_line);
  const atssim::app::Action devices = atssim::app::add_devices_command(cli);
  const atssim::app::Action schedule = atssim::app::add_schedule_command(cli);
  const atssim::app::Action converge = atssim::app::add_converge_command(cli, command_line);
  const atssim::app::Action inspect = atssim::app::add_inspect_command(cli);
  const atssim::app::Action methods = atssim::app::add_methods_command(cli);

  if (argc > 1 && argv[1][0] != '-') {
    bool known = false;
    std::string names;
    for (const CLI::App* sub : cli.get_subcommands({})) {
      known = known || sub->get_name() == argv[1];
      names += (names.empty() ? "" : ", ") + sub->get_name();
    }
    if (!known) {
      fmt::print(stderr, "atssim: unknown command '{}'; the commands are {} (see atssim --help)\n", argv[1], names);
      return 2;
    }
  }
  try {
    cli.parse(argc, argv);
  } catch (const CLI::CallForHelp& e) {
    return cli.exit(e);
  } catch (const CLI::CallForAllHelp& e) {
    return cli.exit(e);
  } catch (const CLI::CallForVersion& e) {
    return cli.exit(e);
  } catch (const CLI::ParseError& e) {
    fmt::print(stderr, "atssim: {}; see atssim --help\n", e.what());
    return 2;
  }

  try {
    for (CLI::App* sub : cli.get_subcommands()) {
      if (sub->get_name() == "run") return run();
      if (sub->get_name() == "devices") return devices();
      if (sub->get_name() == "schedule") return schedule();
      if (sub->get_name() == "converge") return converge();
      if (sub->get_name() == "inspect") return inspect();
      if (sub->get_name() == "methods") return methods();
    }
  } catch (const atssim::Error& e) {
    fmt::print(stderr, "atssim: {}{}\n", e.kind() == atssim::ErrorKind::internal ? "internal error: " : "", e.what());
    return e.exit_code();
  } catch (const std::exception& e) {
    fmt::print(stderr, "atssim: internal error: {}\n", e.what());
    return 1;
  }
  return 2;
}
