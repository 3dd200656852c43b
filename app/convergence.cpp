#include "app/convergence.hpp"

#include "app/scene_checks.hpp"

#include <algorithm>
#include <cstring>

#include <fmt/format.h>

#include "app/collider_motion.hpp"
#include "app/execution.hpp"
#include "app/simulation.hpp"
#include "device/device_set.hpp"
#include "device/plan_executor.hpp"
#include "io/result_reader.hpp"
#include "model/cloth_builder.hpp"
#include "scene/scene_loader.hpp"
#include "solver/method_registry.hpp"
#include "solver/newton/substep_reference.hpp"
#include "util/error.hpp"

namespace atssim::app {

namespace {

using solver::Float4;

std::vector<int> iteration_counts(int max) {
  std::vector<int> ks;
  for (int k = 1; k < max; k *= 2) ks.push_back(k);
  ks.push_back(max);
  return ks;
}

struct Variant {
  std::string name;
  std::string method;
  ExecutionOptions options;
};

// Every method × schedule (× merge strategy for async); async only for
// Gauss-Seidel methods (a Jacobi method's iterations have nothing to relax).
std::vector<Variant> variants_of(const ConvergeOptions& o, const ExecutionOptions& base) {
  std::vector<Variant> out;
  for (const std::string& method : o.methods) {
    const solver::MethodDescription& described = solver::method(method, "--methods");
    for (const std::string& s : o.schedules) {
      ExecutionOptions e = base;
      e.mode = parse_schedule_mode(s);
      e.profile_repetitions = 3;
      if (e.mode != ScheduleMode::async) {
        out.push_back({fmt::format("{}/{}", method, s), method, e});
        continue;
      }
      if (!described.gauss_seidel) continue;
      for (const std::string& m : o.merges) {
        e.merge = plan::parse_merge_strategy(m);
        out.push_back({fmt::format("{}/async/{}", method, m), method, e});
      }
    }
  }
  if (out.empty()) {
    throw input_error(fmt::format(
        "--schedules async applies to Gauss-Seidel methods only ({}), and --methods names none: add single, split or "
        "heft to --schedules",
        solver::method_names([](const solver::MethodDescription& m) { return m.gauss_seidel; })));
  }
  return out;
}

// The state at the end of the newest checkpoint of a run's result file
// (`converge --from`): its positions and velocities, and the colliders
// where they are during the substep after it.
void state_from_result(const std::string& path, const scene::SceneDesc& scene, const model::Model& model,
                       solver::SimLayout& state) {
  const io::Checkpoint point = io::read_checkpoint(path);
  const std::size_t bytes = state.x.size() * sizeof(Float4);
  if (point.positions.size() != bytes || point.velocities.size() != bytes) {
    throw input_error(
        fmt::format("--from {}: its state holds {} bytes of positions, this scene's {} particles "
                    "need {}; pass the result of a run of this scene",
                    path, point.positions.size(), state.x.size(), bytes));
  }
  state.x = plan::values_of<Float4>(point.positions);
  state.v = plan::values_of<Float4>(point.velocities);
  solver::KinematicColliders colliders(model.colliders);
  if (colliders.moving()) {
    const double t = static_cast<double>(point.frame) * scene.simulation.frame_dt;
    state.colliders = colliders.records(t, t + scene.simulation.frame_dt / scene.simulation.substeps);
  }
}

}  // namespace

io::ConvergenceResult run_convergence(const ConvergeOptions& o) {
  if (o.max_iterations < 1 || o.max_iterations > 4096) {
    throw input_error(fmt::format("--iterations {} is out of range; use 1 to 4096", o.max_iterations));
  }
  if (o.frames_before < 0) throw input_error("--frames-before must be ≥ 0");
  const scene::SceneDesc scene = load_scene(o.scene_path, o.overrides);
  const std::vector<Variant> variants = variants_of(o, execution_options(scene));
  for (const std::string& method : o.methods) solver::check_scene(scene, solver::method(method));
  const auto& sim = scene.simulation;
  const double h = sim.frame_dt / sim.substeps;
  const device::DeviceSet devices = open_scene_devices(scene);

  // The state after `frames_before` frames of the scene's own method
  // (solver.method), on one device; or the one a run's result file holds.
  const model::Model model = model::build_model(scene);
  solver::SimLayout state = solver::make_sim_layout(model);
  if (!o.from.empty()) {
    state_from_result(o.from, scene, model, state);
  } else {
    const solver::MethodDescription& own = solver::method(scene.solver.method);
    device::PlanExecutor executor(devices, own.build(state, solver::method_settings(scene, own)));
    solver::KinematicColliders colliders(model.colliders);
    if (colliders.moving()) {
      for (int s = 0; s < o.frames_before * sim.substeps; ++s) {
        pose_colliders(executor, colliders, s * h, (s + 1) * h);
        executor.run_substeps(1);
      }
      // The measured substep sees the colliders where they are during it.
      const double t = o.frames_before * sim.frame_dt;
      state.colliders = colliders.records(t, t + h);
    } else {
      executor.run_substeps(o.frames_before * sim.substeps);
    }
    const plan::PlanState reached = executor.read_state();
    state.x = plan::values_of<Float4>(reached.positions);
    state.v = plan::values_of<Float4>(reached.velocities);
  }

  io::ConvergenceResult result;
  result.command_line = o.command_line;
  result.scene_yaml = scene.yaml_text;
  result.resolved_yaml = scene.resolved_yaml;
  result.frames_before = o.frames_before;
  result.from = o.from;
  result.substep_dt = h;
  const solver::newton::SubstepReference reference = solver::newton::substep_reference(state, h);
  result.energy_start = reference.energy_start;
  result.energy_reference = reference.newton.energy;
  result.newton_iterations = reference.newton.iterations;
  result.newton_relative_gradient = reference.newton.relative_gradient;
  result.newton_status = std::string(solver::newton::to_string(reference.newton.status));
  result.y_floor = reference.y_floor;

  for (const Variant& v : variants) {
    io::ConvergenceTrace trace;
    trace.variant = v.name;
    for (int k : iteration_counts(o.max_iterations)) {
      const solver::MethodDescription& method = solver::method(v.method);
      solver::MethodSettings settings = solver::method_settings(scene, method);
      settings.iterations = k;
      Execution e = prepare_execution(devices, method.build(state, settings), v.options);
      const plan::PlanState start{plan::bytes_of(state.x), plan::bytes_of(state.v), {}};
      std::vector<double> times;
      std::vector<Float4> x;
      for (int r = 0; r < std::max(1, o.timing_repeats); ++r) {
        e.executor->reset(start);
        e.executor->run_substeps(1, true);
        times.push_back(measure_frame(e).makespan_ms);
        x = plan::values_of<Float4>(e.executor->read_state().positions);
      }
      std::nth_element(times.begin(), times.begin() + times.size() / 2, times.end());
      trace.iterations.push_back(k);
      trace.energy.push_back(reference.energy(state, x));
      trace.relative_error.push_back(reference.relative_error(state, x));
      trace.time_ms.push_back(times[times.size() / 2]);
    }
    result.traces.push_back(std::move(trace));
  }
  return result;
}

std::string format_convergence_table(const io::ConvergenceResult& r) {
  std::string out = fmt::format(
      "E0 = {:.9g}, E* = {:.9g} (Newton: {} steps, relative gradient {:.2e}, {}); y_k = (E_k - E*)/(E0 - E*); "
      "float32 resolution {:.2e}\n",
      r.energy_start, r.energy_reference, r.newton_iterations, r.newton_relative_gradient, r.newton_status, r.y_floor);
  if (r.traces.empty()) return out;
  out += fmt::format("{:<36}", "variant");
  for (int k : r.traces.front().iterations) out += fmt::format(" {:>10}", fmt::format("k={}", k));
  out += fmt::format(" {:>12}\n", "ms (k=max)");
  for (const auto& t : r.traces) {
    out += fmt::format("{:<36}", t.variant);
    for (double y : t.relative_error) out += fmt::format(" {:>10.3e}", y);
    out += fmt::format(" {:>12.3f}\n", t.time_ms.back());
  }
  return out;
}

}  // namespace atssim::app
