// `atssim inspect OUT.h5`: what a result file holds, and whether it is complete.
#include <numeric>

#include <fmt/format.h>
#include <CLI/CLI.hpp>

#include "app/commands.hpp"
#include "io/result_reader.hpp"

namespace atssim::app {

Action add_inspect_command(CLI::App& cli) {
  auto path = std::make_shared<std::string>();
  CLI::App* cmd = cli.add_subcommand("inspect", "Summarise a result file: frames, objects, devices, timing, status");
  cmd->add_option("file", *path, "HDF5 file written by atssim run")->required();
  return [path]() {
    const io::ResultSummary s = io::read_summary(*path);
    fmt::print("{}: atssim format {} (atssim {}), created {}\n", *path, s.format_version, s.atssim_version, s.created);
    fmt::print("command:   {}\n", s.command_line);
    if (s.complete) {
      fmt::print("status:    complete\n");
    } else if (!s.error.empty()) {
      fmt::print("status:    failed: {}\n", s.error);
    } else {
      fmt::print("status:    incomplete (the run was stopped or is still writing)\n");
    }
    fmt::print("frames:    {} (t = {:.4g} … {:.4g} s), {} particles\n", s.frames, s.time.empty() ? 0.0 : s.time.front(),
               s.time.empty() ? 0.0 : s.time.back(), s.particles);
    std::string objects;
    for (const auto& o : s.objects) objects += (objects.empty() ? "" : ", ") + o;
    fmt::print("objects:   {}\n", objects);
    std::string devices;
    for (const auto& d : s.devices) devices += (devices.empty() ? "" : "; ") + d;
    fmt::print("devices:   {}\n", devices);
    if (s.frame_ms.size() > 1) {
      const double total = std::accumulate(s.frame_ms.begin() + 1, s.frame_ms.end(), 0.0);
      fmt::print("timing:    {:.2f} ms/frame mean over {} frames\n", total / double(s.frame_ms.size() - 1),
                 s.frame_ms.size() - 1);
    }
    return 0;
  };
}

}  // namespace atssim::app
