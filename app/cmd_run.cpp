// `atssim run SCENE`: simulate and write HDF5.
#include <unistd.h>
#include <chrono>
#include <cstdio>

#include <fmt/format.h>
#include <CLI/CLI.hpp>

#include "app/commands.hpp"
#include "app/run_summary.hpp"
#include "app/simulation.hpp"
#include "app/stop_signals.hpp"
#include "util/error.hpp"

namespace atssim::app {

namespace {

struct RunArgs {
  std::string scene;
  std::string output;
  int frames = 0;
  std::string devices;
  std::string schedule;
  std::string executor;
  std::string memory;
  std::vector<std::string> sets;
  bool quiet = false;
  bool json = false;
  std::string svm;
  std::string method;
  bool resume = false;
  double tolerance = 0.0;
  double budget_ms = 0.0;
  int recheck = -1;
  std::vector<std::string> methods;
};

void print_progress(const RunProgress& p) {
  const double eta_s = p.mean_ms * (p.frames - p.frame) / 1000.0;
  fmt::print(stderr, "\rframe {}/{}  {:.1f} ms/frame  ETA {:.0f} s   ", p.frame, p.frames, p.frame_ms, eta_s);
  if (p.frame == p.frames) fmt::print(stderr, "\n");
}

}  // namespace

Action add_run_command(CLI::App& cli, const std::string& command_line) {
  auto args = std::make_shared<RunArgs>();
  CLI::App* cmd = cli.add_subcommand("run", "Simulate a scene and write the frames to HDF5");
  cmd->add_option("scene", args->scene, "Scene file (YAML, see docs/scene-format.md)")->required();
  cmd->add_option("-o,--output", args->output, "Output HDF5 file (default: the scene's output.path)");
  cmd->add_option("--frames", args->frames, "Number of frames to simulate (1 or more)")
      ->check(CLI::Range(1, 10000000).description("1 or more"));
  cmd->add_option("--method", args->method, "Solver method (the scene's solver.method; see atssim methods)");
  add_accuracy_options(*cmd, args->tolerance, args->budget_ms, args->methods);
  cmd->add_option("--recheck", args->recheck,
                  "With --tolerance or --budget: re-check the choice on the live state every N frames (default 30, "
                  "0 = never)");
  cmd->add_flag("--resume", args->resume,
                "Continue the run a killed or stopped run left at the output path, from its last recorded frame");
  cmd->add_option("--devices", args->devices, "Device spec: default, cpu, gpu, N, cpu/2 (see atssim devices)");
  cmd->add_option("--schedule", args->schedule,
                  "How the substep uses the devices: single, split (blocks divided by device speed), heft, async");
  cmd->add_option("--executor", args->executor,
                  "How devices run the schedule: auto (fused where SVM atomics allow), fused, events")
      ->check(CLI::IsMember({"auto", "fused", "events"}));
  cmd->add_option("--memory", args->memory,
                  "shared (a platform's devices share SVM) or separate (every device its own memory, copies "
                  "through the host)")
      ->check(CLI::IsMember({"shared", "separate"}));
  cmd->add_option("--set", args->sets, "Override a scene key, e.g. --set simulation.substeps=32 (repeatable)");
  cmd->add_flag("-q,--quiet", args->quiet, "Print nothing but errors and warnings");
  cmd->add_flag("--json", args->json,
                "Print one JSON object on stdout summarising the run, also when it fails (docs/run-json.md)");
  cmd->add_option("--svm", args->svm, "Shared virtual memory: auto (fine grain when offered) or coarse")
      ->check(CLI::IsMember({"auto", "coarse", "fine"}));
  return [args, command_line, cmd]() {
    RunOptions options;
    options.scene_path = args->scene;
    options.command_line = command_line;
    options.svm_mode = args->svm;
    options.overrides = args->sets;
    options.resume = args->resume;
    if (cmd->count("--output") > 0 && args->output.empty()) {
      throw input_error("-o/--output: the output path is empty; pass a file name, e.g. -o run.h5");
    }
    if (cmd->count("--devices") > 0 && args->devices.empty()) {
      throw input_error("--devices: the device spec is empty; pass e.g. --devices cpu (see atssim devices)");
    }
    if (cmd->count("--method") > 0 && args->method.empty()) {
      throw input_error("--method: the method is empty; pass one of those atssim methods lists");
    }
    if (cmd->count("--recheck") > 0 && args->recheck < 0) {
      throw input_error(fmt::format("--recheck {}: give a number of frames, 0 (never) or more", args->recheck));
    }
    // --method with a tolerance or a budget: the one method to choose iterations for.
    if (!args->method.empty() && args->methods.empty() && (cmd->count("--tolerance") + cmd->count("--budget")) > 0) {
      args->methods = {args->method};
    }
    push_accuracy_overrides(*cmd, args->tolerance, args->budget_ms, args->methods, options.overrides);
    if (cmd->count("--recheck") > 0) options.overrides.push_back(fmt::format("solver.recheck={}", args->recheck));
    if (!args->method.empty()) options.overrides.push_back("solver.method=" + args->method);
    if (!args->output.empty()) options.overrides.push_back("output.path=" + args->output);
    if (args->frames > 0) options.overrides.push_back("simulation.frames=" + std::to_string(args->frames));
    if (!args->devices.empty()) options.overrides.push_back("devices=" + args->devices);
    if (!args->schedule.empty()) options.overrides.push_back("solver.schedule=" + args->schedule);
    if (!args->executor.empty()) options.overrides.push_back("solver.executor=" + args->executor);
    if (!args->memory.empty()) options.overrides.push_back("memory=" + args->memory);

    const bool show_progress = !args->quiet && isatty(STDERR_FILENO);
    options.warn = [show_progress](const std::string& text) {
      fmt::print(stderr, "{}atssim: warning: {}\n", show_progress ? "\n" : "", text);
    };
    // The first Ctrl-C stops the run before its next substep (the frames
    // written are kept); a second one ends the process at once.
    watch_stop_signals();
    const auto start = std::chrono::steady_clock::now();
    RunResult r;
    RunSummaryInput summary;
    summary.scene_path = args->scene;
    summary.command_line = command_line;
    const auto print_summary = [&]() {
      summary.wall_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
      fmt::print("{}", run_summary_json(r, summary));
      std::fflush(stdout);
    };
    try {
      run_simulation(options, r, show_progress ? print_progress : std::function<void(const RunProgress&)>{});
    } catch (const std::exception& e) {
      if (args->json) {
        const auto* error = dynamic_cast<const Error*>(&e);
        summary.status = error && error->kind() == ErrorKind::input ? RunStatus::input_error
                         : stop_requested()                         ? RunStatus::interrupted
                                                                    : RunStatus::failed;
        summary.error = e.what();
        print_summary();
      }
      throw;  // main prints the message and exits with its code
    }
    if (args->json) {
      print_summary();
    } else if (!args->quiet) {
      fmt::print("wrote {}: {} frames ({} simulated), {} particles, {:.2f} ms/frame on {}\n", r.output_path,
                 r.frames_written, r.frames_simulated, r.particles, r.mean_frame_ms, r.device);
    }
    return 0;
  };
}

}  // namespace atssim::app
