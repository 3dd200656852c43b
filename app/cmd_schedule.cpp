// `atssim schedule SCENE`: the substep's task graph and its predicted
// schedule, without simulating: as a table, JSON, Graphviz dot, or the cost
// table as CSV (which --costs reads back). With --tolerance or --budget:
// the table of the probe a run would choose from.
#include <algorithm>
#include <cmath>

#include <fmt/format.h>
#include <CLI/CLI.hpp>

#include "app/accuracy_control.hpp"
#include "app/accuracy_probe.hpp"
#include "app/commands.hpp"
#include "app/execution.hpp"
#include "app/scene_checks.hpp"
#include "app/simulation.hpp"
#include "device/device_set.hpp"
#include "io/cost_file.hpp"
#include "model/cloth_builder.hpp"
#include "plan/substep_plan.hpp"
#include "scene/scene_loader.hpp"
#include "util/error.hpp"

namespace atssim::app {

namespace {

struct ScheduleArgs {
  std::string scene, devices, schedule, executor, memory, costs, method;
  std::vector<std::string> sets;
  bool json = false, dot = false, csv = false;
  double tolerance = 0.0, budget_ms = 0.0;
  std::vector<std::string> methods;
};

// `schedule --tolerance` / `--budget`: the probe's table, without running.
int print_probe(const scene::SceneDesc& scene) {
  const device::DeviceSet devices = open_scene_devices(scene);
  const model::Model model = model::build_model(scene);
  AccuracyProbe probe(scene, devices);
  const ProbeTable table = probe.probe(solver::make_sim_layout(model), 0, AccuracyControl::kProbeSubsteps);
  fmt::print("{}", format_probe_table(table));
  if (table.goal.tolerance > 0.0 && !table.resolved) {
    fmt::print(
        "the start state does not resolve the tolerance: a run starts with the scene's own settings and "
        "re-checks every frame until a state does\n");
  } else if (!table.choice.chosen) {
    std::fflush(stdout);
    throw input_error(none_meets_message(table, probe.max_iterations()));
  }
  return 0;
}

std::string kind_name(const sched::Task& task) {
  return task.kind == sched::kMixedKind ? "mixed" : std::string(plan::to_string(plan::kind_of(task)));
}

std::string json_escape(const std::string& s) {
  std::string out;
  for (char c : s) {
    if (c == '"' || c == '\\') out += '\\';
    out += c;
  }
  return out;
}

void print_table(const PlannedSchedule& p, const std::string& mode) {
  const auto& g = p.plan.graph;
  fmt::print(
      "substep: {} tasks, {} edges; schedule '{}' on {} device(s); predicted makespan {:.4f} ms; {} "
      "cross-device waits\n",
      g.size(), g.edge_count(), mode, p.costs.devices, p.schedule.makespan_ms, p.waits.size());
  const int groups = p.merge_group.empty() ? 0 : *std::max_element(p.merge_group.begin(), p.merge_group.end()) + 1;
  if (groups > 0) {
    fmt::print("task merging: {} merged tasks of colour blocks (column 'merged'); HEFT without merging: {:.4f} ms\n",
               groups, p.unmerged_makespan_ms);
  }
  if (mode == "split" && !p.split_fractions.empty()) {
    fmt::print("split fractions:");
    for (double f : p.split_fractions) fmt::print(" {:.3f}", f);
    fmt::print("\n");
  }
  fmt::print("{:>5}  {:<24} {:<16} {:>4} {:>5}  {:>6}  {:>10}  {:>10}{}\n", "id", "task", "kind", "it", "block",
             "device", "start_ms", "finish_ms", groups > 0 ? "  merged" : "");
  for (sched::TaskId t = 0; t < g.size(); ++t) {
    const auto& task = g.task(t);
    const auto& slot = p.schedule.slot(t);
    fmt::print("{:>5}  {:<24} {:<16} {:>4} {:>5}  {:>6}  {:>10.4f}  {:>10.4f}{}\n", t, task.name, kind_name(task),
               task.iteration, task.block, p.schedule.device_of(t), slot.start_ms, slot.finish_ms,
               groups > 0 ? fmt::format("  {:>6}", p.merge_group[t]) : "");
  }
}

void print_json(const PlannedSchedule& p, const std::string& mode) {
  const auto& g = p.plan.graph;
  fmt::print("{{\n  \"schedule\": \"{}\",\n  \"devices\": {},\n  \"makespan_ms\": {:.6f},\n", mode, p.costs.devices,
             p.schedule.makespan_ms);
  if (std::isfinite(p.unmerged_makespan_ms))
    fmt::print("  \"unmerged_makespan_ms\": {:.6f},\n", p.unmerged_makespan_ms);
  fmt::print("  \"tasks\": [\n");
  for (sched::TaskId t = 0; t < g.size(); ++t) {
    const auto& task = g.task(t);
    const auto& slot = p.schedule.slot(t);
    std::string costs;
    for (std::size_t d = 0; d < p.costs.devices; ++d) {
      // A task a device cannot run costs inf, which JSON has no number for.
      const double c = p.costs.at(t, d);
      costs += fmt::format("{}{}", d ? ", " : "", std::isfinite(c) ? fmt::format("{:.6f}", c) : "null");
    }
    fmt::print(
        "    {{\"id\": {}, \"name\": \"{}\", \"kind\": \"{}\", \"iteration\": {}, \"block\": {}, \"device\": {}, "
        "\"start_ms\": {:.6f}, \"finish_ms\": {:.6f}, \"cost_ms\": [{}], \"merge_group\": {}}}{}\n",
        t, json_escape(task.name), kind_name(task), task.iteration, task.block, p.schedule.device_of(t), slot.start_ms,
        slot.finish_ms, costs, t < p.merge_group.size() ? p.merge_group[t] : -1, t + 1 < g.size() ? "," : "");
  }
  fmt::print("  ],\n  \"edges\": [");
  bool first = true;
  for (sched::TaskId t = 0; t < g.size(); ++t) {
    for (const auto& e : g.successors(t)) {
      fmt::print("{}[{}, {}]", first ? "" : ", ", e.from, e.to);
      first = false;
    }
  }
  fmt::print("],\n  \"waits\": [");
  for (std::size_t i = 0; i < p.waits.size(); ++i) {
    const auto& w = p.waits[i];
    fmt::print("{}{{\"producer\": {}, \"producer_device\": {}, \"consumer\": {}, \"consumer_device\": {}}}",
               i ? ", " : "", w.producer, w.producer_device, w.consumer, w.consumer_device);
  }
  fmt::print("]\n}}\n");
}

void print_dot(const PlannedSchedule& p, const std::string& mode) {
  static const char* colours[] = {"lightblue", "orange", "palegreen", "pink", "khaki", "plum"};
  const auto& g = p.plan.graph;
  fmt::print("digraph substep {{\n  label=\"schedule {} — makespan {:.4f} ms\";\n  node [shape=box, style=filled];\n",
             mode, p.schedule.makespan_ms);
  for (sched::TaskId t = 0; t < g.size(); ++t) {
    const auto d = p.schedule.device_of(t);
    fmt::print("  t{} [label=\"{}\\ndevice {}\", fillcolor={}];\n", t, g.task(t).name, d, colours[d % 6]);
  }
  for (sched::TaskId t = 0; t < g.size(); ++t) {
    for (const auto& e : g.successors(t)) {
      const bool cross = p.schedule.device_of(e.from) != p.schedule.device_of(e.to);
      fmt::print("  t{} -> t{}{};\n", e.from, e.to, cross ? " [color=red, penwidth=2]" : "");
    }
  }
  fmt::print("}}\n");
}

}  // namespace

Action add_schedule_command(CLI::App& cli) {
  auto args = std::make_shared<ScheduleArgs>();
  CLI::App* cmd = cli.add_subcommand("schedule", "Print the substep's task graph and its predicted schedule");
  cmd->add_option("scene", args->scene, "Scene file (YAML)")->required();
  cmd->add_option("--devices", args->devices, "Device spec to profile, e.g. cpu/2 (see atssim devices)");
  cmd->add_option("--schedule", args->schedule, "single, split or heft (default: the scene's solver.schedule)");
  cmd->add_option("--executor", args->executor, "auto, fused or events (default: the scene's solver.executor)")
      ->check(CLI::IsMember({"auto", "fused", "events"}));
  cmd->add_option("--memory", args->memory,
                  "shared (a platform's devices share SVM) or separate (every device its own memory, copies "
                  "through the host)")
      ->check(CLI::IsMember({"shared", "separate"}));
  cmd->add_option("--costs", args->costs, "Cost table CSV (as --csv prints it) instead of profiling the devices");
  cmd->add_option("--set", args->sets, "Override a scene key (repeatable)");
  cmd->add_option("--method", args->method, "Solver method (the scene's solver.method; see atssim methods)");
  add_accuracy_options(*cmd, args->tolerance, args->budget_ms, args->methods);
  auto* json = cmd->add_flag("--json", args->json, "Print JSON");
  auto* dot = cmd->add_flag("--dot", args->dot, "Print a Graphviz graph, tasks coloured by device");
  auto* csv = cmd->add_flag("--csv", args->csv, "Print the cost table (ms per task and device) as CSV");
  json->excludes(dot)->excludes(csv);
  dot->excludes(csv);
  return [args, cmd]() {
    std::vector<std::string> overrides = args->sets;
    for (const char* flag : {"--devices", "--method", "--costs"}) {
      if (cmd->count(flag) > 0 && (std::string(flag) == "--devices"  ? args->devices.empty()
                                   : std::string(flag) == "--method" ? args->method.empty()
                                                                     : args->costs.empty())) {
        throw input_error(fmt::format("{}: the value is empty; see atssim schedule --help", flag));
      }
    }
    if (!args->method.empty() && args->methods.empty() && (cmd->count("--tolerance") + cmd->count("--budget")) > 0) {
      args->methods = {args->method};
    }
    push_accuracy_overrides(*cmd, args->tolerance, args->budget_ms, args->methods, overrides);
    if (!args->method.empty()) overrides.push_back("solver.method=" + args->method);
    if (!args->devices.empty()) overrides.push_back("devices=" + args->devices);
    if (!args->schedule.empty()) overrides.push_back("solver.schedule=" + args->schedule);
    if (!args->executor.empty()) overrides.push_back("solver.executor=" + args->executor);
    if (!args->memory.empty()) overrides.push_back("memory=" + args->memory);
    const scene::SceneDesc scene = load_scene(args->scene, overrides);
    if (scene.solver.accuracy.active()) {
      if (args->json || args->dot || args->csv || !args->costs.empty()) {
        throw input_error(
            "--tolerance / --budget print the probe's table as text; drop --json, --dot, --csv and --costs");
      }
      return print_probe(scene);
    }
    const ScheduleMode mode = parse_schedule_mode(scene.solver.schedule);
    const plan::SubstepPlan base = substep_plan_for(scene);

    PlannedSchedule planned;
    if (!args->costs.empty()) {
      // The file's column count is the device count; its rows are the tasks
      // of the plan cut into that many equal parts.
      const std::size_t columns = io::cost_file_devices(args->costs);
      const auto file = io::read_cost_file(args->costs, cut_for_mode(base, mode, columns).graph);
      planned = schedule_from_costs(base, mode, file.costs, file.latency_ms, scene.solver.task_merging);
    } else {
      const device::DeviceSet devices = open_scene_devices(scene);
      Execution e = prepare_execution(devices, base, execution_options(scene));
      planned.plan = e.plan();
      planned.costs = e.costs.costs();
      planned.links = e.costs.links();
      planned.schedule = e.schedule;
      planned.waits = e.waits;
      planned.split_fractions = e.split_fractions;
      planned.merge_group = e.merge_group;
      planned.unmerged_makespan_ms = e.unmerged_makespan_ms;
    }
    const std::string mode_name = to_string(mode);
    if (args->json) {
      print_json(planned, mode_name);
    } else if (args->dot) {
      print_dot(planned, mode_name);
    } else if (args->csv) {
      const std::size_t n = planned.links.devices;
      fmt::print("{}",
                 io::format_cost_file(planned.plan.graph, planned.costs, n > 1 ? planned.links.latency_ms[1] : 0.0));
    } else {
      print_table(planned, mode_name);
    }
    return 0;
  };
}

}  // namespace atssim::app
