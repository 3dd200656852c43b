#include "app/simulation.hpp"

#include <algorithm>

#include <atomic>
#include <chrono>
#include <cmath>

#include <fmt/format.h>

#include "app/execution.hpp"
#include "device/device_set.hpp"
#include "device/plan_executor.hpp"
#include "io/result_writer.hpp"
#include "model/cloth_builder.hpp"
#include "scene/scene_loader.hpp"
#include "solver/method_plan.hpp"
#include "solver/xpbd/xpbd_plan.hpp"
#include "util/error.hpp"

namespace atssim::app {

namespace {

std::atomic<bool> g_stop{false};

// The first particle whose position is not finite or flew implausibly far.
int find_blow_up(const std::vector<float>& xyz) {
  for (std::size_t i = 0; i < xyz.size(); ++i) {
    if (!std::isfinite(xyz[i]) || std::abs(xyz[i]) > 1e6f) return static_cast<int>(i / 3);
  }
  return -1;
}

device::SvmMode svm_mode(const std::string& text) {
  if (text == "coarse") return device::SvmMode::coarse;
  if (text == "fine") return device::SvmMode::fine;
  return device::SvmMode::automatic;
}

void record_schedule(io::ResultWriter& writer, int frame, const sched::Schedule& used,
                     const std::vector<sched::Wait>& waits, const std::vector<device::TaskTiming>& timings) {
  std::vector<io::ScheduledTask> rows;
  double measured = 0.0;
  for (const auto& t : timings) {
    const sched::Slot& slot = used.slot(t.task);
    rows.push_back({t.task, static_cast<int>(t.device), slot.start_ms, slot.finish_ms, t.start_ms, t.finish_ms});
    measured = std::max(measured, t.finish_ms);
  }
  writer.append_schedule(frame, rows, waits, used.makespan_ms, measured);
}

// Keeps only what output needs (object topology and rest shape).
void release_simulation_state(model::Model& model) {
  model = model::Model{{}, {}, {}, std::move(model.objects), model.gravity, {}, model.ground};
}

}  // namespace

void request_stop() { g_stop = true; }

solver::MethodOptions method_options(const scene::SolverDesc& solver) {
  return {solver.chebyshev_rho, solver.jacobi_step, solver.stencil_step, solver.momentum};
}

solver::SubstepPlan substep_plan_for(const scene::SceneDesc& scene) {
  const auto& sim = scene.simulation;
  const model::Model model = model::build_model(scene);
  return solver::make_method_plan(scene.solver.method, solver::make_sim_layout(model),
                                  sim.frame_dt / sim.substeps, sim.iterations, method_options(scene.solver));
}

RunResult run_simulation(const RunOptions& options, const std::function<void(const RunProgress&)>& progress) {
  g_stop = false;
  const scene::SceneDesc scene = scene::load_scene_file(options.scene_path, options.overrides);
  scene::check_method_support(scene, scene.solver.method);
  const device::DeviceSet devices = device::DeviceSet::open(scene.devices);
  const auto& sim = scene.simulation;
  const solver::xpbd::XpbdSettings settings{sim.frame_dt / sim.substeps, sim.iterations};

  // Each stage's data is released once the next holds it, so the peak memory
  // is one stage's worth, not the sum (docs/benchmarks.md: bytes per vertex).
  model::Model model = model::build_model(scene);
  const std::size_t particles = model.particles.size();
  solver::SimLayout layout = solver::make_sim_layout(model);
  release_simulation_state(model);
  solver::SubstepPlan plan =
      solver::make_method_plan(scene.solver.method, layout, settings.substep_dt, settings.iterations,
                               method_options(scene.solver));
  layout = {};
  ExecutionOptions exec_options;
  exec_options.mode = parse_schedule_mode(scene.solver.schedule);
  if (exec_options.mode == ScheduleMode::async && !solver::is_gauss_seidel(scene.solver.method)) {
    throw input_error(fmt::format("schedule 'async' relaxes Gauss-Seidel iterations, and '{}' iterates Jacobi sweeps "
                                  "that already run on every device with one synchronisation each: use --schedule "
                                  "split or heft",
                                  scene.solver.method));
  }
  exec_options.svm = svm_mode(options.svm_mode);
  exec_options.async_depth = scene.solver.async_depth;
  exec_options.merge = solver::parse_merge_strategy(scene.solver.merge);
  exec_options.async_latest = scene.solver.async_latest;
  exec_options.replay = scene.solver.replay;
  Execution execution = prepare_execution(devices, plan, exec_options);
  plan = {};
  for (auto& buffer : execution.plan->buffers) std::vector<std::byte>().swap(buffer.initial);
  device::PlanExecutor& executor = *execution.executor;

  io::RunInfo info{options.command_line, scene.yaml_text, scene.resolved_yaml, devices.infos(), {}};
  info.schedule.mode = to_string(exec_options.mode);
  info.schedule.graph = &execution.plan->graph;
  info.schedule.costs = execution.profiled;
  info.schedule.latency_ms = execution.links.latency_ms;
  info.schedule.split_fractions = execution.split_fractions;
  io::ResultWriter writer(scene.output.path, info, model);

  RunResult result;
  result.output_path = scene.output.path;
  result.particles = particles;
  result.device = devices.info(0).name;
  std::vector<float> xyz;
  executor.read_positions(xyz);
  writer.append_frame(0.0, xyz, 0.0);

  double total_ms = 0.0;
  try {
    for (int frame = 1; frame <= sim.frames; ++frame) {
      if (g_stop) throw runtime_error(fmt::format("interrupted before frame {}", frame));
      const auto start = std::chrono::steady_clock::now();
      executor.enqueue_substeps(sim.substeps, true);
      executor.read_positions(xyz);
      const double ms = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
      // Costs from this frame's profiling events refit the table; the
      // schedule follows (paper §5: re-profiled every frame with smoothing).
      const sched::Schedule used = execution.schedule;
      const std::vector<sched::Wait> used_waits = execution.waits;
      const auto schedule_start = std::chrono::steady_clock::now();
      const auto timings = refit_and_reschedule(execution, exec_options);
      const double schedule_ms =
          std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - schedule_start).count();
      if (const int p = find_blow_up(xyz); p >= 0) {
        throw runtime_error(fmt::format("frame {}: the simulation blew up (particle {} is at a non-finite or "
                                        "implausible position); use more substeps or iterations, or softer "
                                        "materials",
                                        frame, p));
      }
      total_ms += ms;
      result.frames_simulated = frame;
      if (frame % scene.output.stride == 0) {
        record_schedule(writer, frame, used, used_waits, timings);
        writer.append_frame(frame * sim.frame_dt, xyz, ms, schedule_ms);
      }
      if (progress) progress({frame, sim.frames, ms, total_ms / frame});
    }
  } catch (const std::exception& e) {  // atssim::Error included
    const int kept = writer.frames_written();
    writer.fail(e.what());
    throw runtime_error(fmt::format("{} ({} frames kept in {})", e.what(), kept, writer.path()));
  }
  writer.finish();
  result.frames_written = writer.frames_written();
  result.mean_frame_ms = result.frames_simulated > 0 ? total_ms / result.frames_simulated : 0.0;
  return result;
}

}  // namespace atssim::app
