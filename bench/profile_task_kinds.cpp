// What each kind of task of a scene's plan costs on the devices, profiled,
// against plan/task_work's model: the numbers its weights came from, for
// any scene (`run --tolerance` ranks its choices by that model).
//   profile_task_kinds SCENE [--method M] [--iterations K] [--set key=value]...
// Run it under /work/bin/cpu-quiet: a loaded machine profiles its load.
#include <map>

#include <fmt/format.h>
#include <CLI/CLI.hpp>

#include "app/execution.hpp"
#include "app/scene_checks.hpp"
#include "app/simulation.hpp"
#include "device/plan_executor.hpp"
#include "model/cloth_builder.hpp"
#include "plan/task_work.hpp"
#include "scene/scene_desc.hpp"
#include "solver/method_registry.hpp"

using namespace atssim;

int main(int argc, char** argv) {
  CLI::App cli{"Profiled cost of each task kind of a scene's plan against the cost model"};
  std::string scene_path, method_name;
  int iterations = 4, repetitions = 7;
  std::vector<std::string> sets;
  cli.add_option("scene", scene_path)->required();
  cli.add_option("--method", method_name, "Solver method (default: the scene's)");
  cli.add_option("--iterations", iterations)->capture_default_str();
  cli.add_option("--repetitions", repetitions)->capture_default_str();
  cli.add_option("--set", sets);
  CLI11_PARSE(cli, argc, argv);
  try {
    if (!method_name.empty()) sets.push_back("solver.method=" + method_name);
    const scene::SceneDesc scene = app::load_scene(scene_path, sets);
    const solver::MethodDescription& method = solver::method(scene.solver.method);
    solver::MethodSettings settings = solver::method_settings(scene, method);
    settings.iterations = iterations;
    const device::DeviceSet devices = app::open_scene_devices(scene);
    device::PlanExecutor executor(devices, method.build(solver::make_sim_layout(model::build_model(scene)), settings));
    const sched::CostTable costs = app::profile(executor, repetitions);
    const plan::SubstepPlan& p = executor.plan();
    struct Row {
      int tasks = 0;
      double items = 0, measured_us = 0, model_us = 0;
    };
    std::map<std::string, Row> kinds;
    Row total;
    for (sched::TaskId t = 0; t < p.graph.size(); ++t) {
      Row& r = kinds[std::string(plan::to_string(plan::kind_of(p.graph.task(t))))];
      for (const auto& l : p.launches[t]) r.items += l.range.count;
      r.tasks += 1;
      r.measured_us += 1e3 * costs.at(t, 0);
      r.model_us += plan::task_work_us(p, t);
      total.measured_us += 1e3 * costs.at(t, 0);
      total.model_us += plan::task_work_us(p, t);
    }
    fmt::print(
        "{} at {} iterations on {}: {} particles; device 0 measured {:.1f} us per substep, the model {:.1f} us\n",
        method.name, iterations, devices.info(0).name, p.particle_count, total.measured_us, total.model_us);
    fmt::print("{:<16} {:>6} {:>9} {:>12} {:>10} {:>13} {:>12}\n", "kind", "tasks", "items", "measured us", "model us",
               "measured/model", "ns per item");
    for (const auto& [kind, r] : kinds) {
      fmt::print("{:<16} {:>6} {:>9.0f} {:>12.1f} {:>10.1f} {:>13.2f} {:>12.1f}\n", kind, r.tasks, r.items,
                 r.measured_us, r.model_us, r.measured_us / r.model_us,
                 r.items > 0 ? 1e3 * (r.measured_us - 1.5 * r.tasks) / r.items : 0.0);
    }
  } catch (const std::exception& e) {
    fmt::print(stderr, "profile_task_kinds: {}\n", e.what());
    return 2;
  }
  return 0;
}
