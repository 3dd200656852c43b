#include "app/simulation.hpp"

#include <algorithm>

#include <atomic>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <future>
#include <limits>
#include <optional>
#include <stdexcept>
#include <string_view>

#include <fmt/format.h>

#include "app/accuracy_control.hpp"
#include "app/blow_up.hpp"
#include "app/collider_motion.hpp"
#include "app/energy_growth.hpp"
#include "app/execution.hpp"
#include "app/scene_checks.hpp"
#include "device/device_set.hpp"
#include "device/plan_executor.hpp"
#include "io/output_health.hpp"
#include "io/result_writer.hpp"
#include "model/cloth_builder.hpp"
#include "scene/scene_loader.hpp"
#include "scene/scene_yaml.hpp"
#include "solver/contact/contact_summary.hpp"
#include "solver/contact/surface_contacts.hpp"
#include "solver/method_registry.hpp"
#include "util/error.hpp"

namespace atssim::app {

namespace {

std::atomic<bool> g_stop{false};

// xyz triplets of a float4 buffer's bytes (positions, velocities).
std::vector<float> xyz_of(const std::vector<std::byte>& raw) {
  const auto* p = reinterpret_cast<const float*>(raw.data());
  const std::size_t n = raw.size() / (4 * sizeof(float));
  std::vector<float> xyz(3 * n);
  for (std::size_t i = 0; i < n; ++i) {
    for (int k = 0; k < 3; ++k) xyz[3 * i + k] = p[4 * i + k];
  }
  return xyz;
}

// Runs one frame's substeps one at a time, so that a stop request (Ctrl-C)
// is honoured within a substep and moving colliders are posed for each;
// the last substep is timed task by task. A frame's result depends only on
// the state it starts from (PlanState: what a checkpoint holds), so resumed
// and repeated frames are those of an uninterrupted run.
void run_frame(device::PlanExecutor& executor, solver::KinematicColliders& colliders, int substeps, int frame,
               double frame_dt) {
  const double h = frame_dt / substeps;
  for (int s = 0; s < substeps; ++s) {
    if (g_stop) throw runtime_error(fmt::format("interrupted in frame {} (substep {} of {})", frame, s, substeps));
    const double t0 = (frame - 1) * frame_dt + s * h;
    pose_colliders(executor, colliders, t0, t0 + h);
    executor.run_substeps(1, s + 1 == substeps);
    executor.finish();
  }
}

device::SvmMode svm_mode(const std::string& text) {
  if (text == "coarse") return device::SvmMode::coarse;
  if (text == "fine") return device::SvmMode::fine;
  return device::SvmMode::automatic;
}

// Every task of the schedule that ran, with what was measured of it (NaN
// where a fused launch without a task clock timed only the whole launch).
// The schedule a frame ran: the slots, the waits between devices, each
// task's merged task (heft; empty: none) and HEFT's makespan without merging.
struct UsedSchedule {
  const sched::Schedule& schedule;
  const std::vector<sched::Wait>& waits;
  const std::vector<int>& merge_group;
  double unmerged_makespan_ms;
};

void record_schedule(io::ResultWriter& writer, int frame, const UsedSchedule& used, const FrameMeasurement& measured) {
  std::vector<io::ScheduledTask> rows;
  const auto group = [&](sched::TaskId t) { return t < used.merge_group.size() ? used.merge_group[t] : -1; };
  if (!measured.timings.empty()) {
    for (const auto& t : measured.timings) {
      const sched::Slot& slot = used.schedule.slot(t.task);
      rows.push_back(
          {t.task, static_cast<int>(t.device), slot.start_ms, slot.finish_ms, t.start_ms, t.finish_ms, group(t.task)});
    }
  } else {
    const double nan = std::numeric_limits<double>::quiet_NaN();
    for (std::size_t d = 0; d < used.schedule.devices.size(); ++d) {
      for (const sched::Slot& slot : used.schedule.devices[d]) {
        rows.push_back({slot.task, static_cast<int>(d), slot.start_ms, slot.finish_ms, nan, nan, group(slot.task)});
      }
    }
  }
  writer.append_schedule(frame, rows, used.waits, used.schedule.makespan_ms, measured.makespan_ms, measured.bytes_moved,
                         used.unmerged_makespan_ms);
}

io::RunInfo run_info(const RunOptions& options, const scene::SceneDesc& scene, const device::DeviceSet& devices,
                     const Execution& e, const ExecutionOptions& exec_options) {
  io::RunInfo info{options.command_line, scene.yaml_text, scene.resolved_yaml, {}, {}};
  for (const device::DeviceInfo& d : devices.infos()) {
    info.devices.push_back({d.name, d.vendor, d.type, d.platform, d.version, device::svm_text(d.svm), d.compute_units,
                            d.index, d.sub_device});
  }
  info.schedule.mode = to_string(exec_options.mode);
  info.schedule.executor = std::string(device::to_string(e.executor->kind()));
  const auto& graph = e.plan().graph;
  for (const sched::Task& t : graph.tasks()) {
    info.schedule.tasks.push_back(
        {t.name, std::string(plan::to_string(plan::kind_of(t))), t.iteration, t.block, t.part});
  }
  for (sched::TaskId t = 0; t < graph.size(); ++t) {
    for (const sched::Edge& edge : graph.successors(t)) {
      info.schedule.edges.emplace_back(static_cast<int>(edge.from), static_cast<int>(edge.to));
    }
  }
  info.schedule.costs = e.costs.profiled();
  info.schedule.latency_ms = e.costs.links().latency_ms;
  info.schedule.memory = e.executor->memories() > 1 ? "separate" : "shared";
  if (e.executor->memories() > 1) info.schedule.ms_per_byte = e.costs.links().ms_per_weight;
  info.schedule.split_fractions = e.split_fractions;
  return info;
}

// A frame's /contact record: the colliders measured here, the surfaces
// (when the scene has a contact surface) as `surfaces` measured them.
io::ContactFrame contact_frame(const solver::KinematicColliders& colliders, const std::vector<float>& xyz,
                               const std::optional<solver::SurfaceContacts>& surfaces) {
  const solver::ContactSummary s = solver::summarize_contacts(colliders.current(), xyz, colliders.count());
  io::ContactFrame c{s.active, s.min_distance, s.max_penetration};
  if (surfaces) {
    c.surface_pairs = surfaces->pairs();
    c.surface_max_penetration = surfaces->max_penetration;
    c.surface_crossings = surfaces->crossings;
  }
  return c;
}

// The surface figures of a frame, measured on another thread while the host
// does the rest of its work on the frame (refit, blow-up check, state read);
// nothing when the scene has no contact surface. `xyz` must stay as it is
// until get().
class SurfaceMeasurement {
 public:
  SurfaceMeasurement() = default;
  SurfaceMeasurement(const std::optional<solver::SurfaceContactCheck>& check, const std::vector<float>& xyz) {
    if (check) pending_ = std::async(std::launch::async, [&check, &xyz] { return check->measure(xyz); });
  }
  std::optional<solver::SurfaceContacts> get() {
    if (!pending_.valid()) return std::nullopt;
    return pending_.get();
  }

 private:
  std::future<solver::SurfaceContacts> pending_;
};

// Once per run, the first written frame whose surfaces crossed: a warning,
// or with contact.strict the run's failure (after the frame is written).
class CrossingReport {
 public:
  CrossingReport(bool strict, std::function<void(const std::string&)> warn) : strict_(strict), warn_(std::move(warn)) {}
  void check(int frame, const io::ContactFrame& c) {
    if (c.surface_crossings <= 0 || reported_) return;
    const std::string what =
        fmt::format("{} edge-triangle crossing{}", c.surface_crossings, c.surface_crossings == 1 ? "" : "s");
    if (strict_) {
      throw runtime_error(
          fmt::format("frame {}: surfaces crossed ({}) and contact.strict is true; use more substeps, a larger "
                      "contact.thickness or contact.stiffness",
                      frame, what));
    }
    reported_ = true;
    const std::string text = fmt::format(
        "surfaces crossed in frame {} ({}); the contact did not keep them apart (more substeps, a larger "
        "contact.thickness or contact.stiffness may; contact.strict: true makes this an error)",
        frame, what);
    if (warn_) {
      warn_(text);
    } else {
      fmt::print(stderr, "atssim: warning: {}\n", text);
    }
  }

 private:
  bool strict_ = false;
  std::function<void(const std::string&)> warn_;
  bool reported_ = false;
};

constexpr const char* kInterruptedSetUp =
    "interrupted during device set-up (building and profiling the kernels); nothing was written";

// Device set-up (opening devices, building and profiling the kernels) runs
// to its end after a Ctrl-C; whatever it fails with then (a driver cut short),
// the run was interrupted.
template <typename Step>
auto during_set_up(Step&& step) -> decltype(step()) {
  try {
    return step();
  } catch (const std::exception&) {
    if (g_stop) throw runtime_error(kInterruptedSetUp);
    throw;
  }
}

// The scene as a choice of `--tolerance` / `--budget` runs it.
void apply_choice(scene::SceneDesc& scene, const SolverChoice& choice) {
  scene.solver.method = choice.method;
  scene.simulation.iterations = choice.iterations;
  scene.solver.schedule = choice.schedule;
}

// Keeps only what output needs (object topology and rest shape).
void release_simulation_state(model::Model& model) {
  model = model::Model{{}, {}, {}, std::move(model.objects), model.gravity, {}, model.ground};
}

// A bug on demand, so that a test drives one through the binary as a user
// would meet it (tests/app/test_error_kinds.cpp): ATSSIM_TEST_FAULT=internal
// throws an internal atssim::Error in frame 2, =exception a std::logic_error
// (a library's exception), both after frames were written.
void injected_fault(int frame) {
  if (frame != 2) return;
  const char* const fault = std::getenv("ATSSIM_TEST_FAULT");
  if (fault == nullptr) return;
  const std::string_view what = fault;
  if (what == "internal") throw internal_error("ATSSIM_TEST_FAULT: an internal fault injected in frame 2");
  if (what == "exception") throw std::logic_error("ATSSIM_TEST_FAULT: a std::logic_error injected in frame 2");
}

}  // namespace

void request_stop() { g_stop = true; }
bool stop_requested() { return g_stop; }

scene::SceneDesc load_scene(const std::string& path, std::span<const std::string> overrides) {
  scene::SceneDesc scene = scene::load_scene_file(path, overrides);
  const solver::MethodDescription& method = solver::method(scene.solver.method, scene.solver.method_where);
  solver::check_scene(scene, method);
  auto& given = scene.solver.method_options;
  for (const solver::MethodOption& o : method.options) {
    const bool set = std::any_of(given.begin(), given.end(), [&](const auto& g) { return g.key == o.key; });
    if (!set && !o.depends_on_scene) given.push_back({std::string(o.key), o.default_text(), ""});
  }
  scene.resolved_yaml = scene::to_resolved_yaml(scene);
  return scene;
}

plan::SubstepPlan substep_plan_for(const scene::SceneDesc& scene) {
  return with_stiffness_line(
      scene, [&] { return solver::build_plan(scene, solver::method(scene.solver.method, scene.solver.method_where)); });
}

RunResult run_simulation(const RunOptions& options, const std::function<void(const RunProgress&)>& progress) {
  RunResult result;
  run_simulation(options, result, progress);
  return result;
}

void run_simulation(const RunOptions& options, RunResult& result,
                    const std::function<void(const RunProgress&)>& progress) {
  g_stop = false;
  result = RunResult{};
  scene::SceneDesc scene = load_scene(options.scene_path, options.overrides);
  // Before the devices: an output path that cannot be written is refused in
  // a moment, not after the kernels were built.
  io::check_output_folder(scene.output.path);
  const device::DeviceSet devices = during_set_up([&] { return open_scene_devices(scene); });
  // A tolerance or a budget: the probe chooses the method, iterations and
  // schedule before anything is written (docs/accuracy.md).
  std::optional<model::Model> probed;
  std::optional<AccuracyControl> tuning;
  if (scene.solver.accuracy.active()) {
    result.tuned = true;
    result.tolerance = scene.solver.accuracy.tolerance;
    result.budget_ms = scene.solver.accuracy.budget_ms;
    result.recheck = scene.solver.accuracy.recheck;
    probed = model::build_model(scene);
    tuning.emplace(scene, devices, *probed, options.warn, options.cost_scale);
    if (!options.resume) apply_choice(scene, tuning->start(solver::make_sim_layout(*probed)));
  }
  const solver::MethodDescription& method = solver::method(scene.solver.method);
  const solver::MethodSettings settings = solver::method_settings(scene, method);
  check_schedule_fits(scene, method, settings, devices.size());
  const auto& sim = scene.simulation;

  // Each stage's data is released once the next holds it, so the peak memory
  // is one stage's worth, not the sum (docs/benchmarks.md: bytes per vertex).
  model::Model model = probed ? std::move(*probed) : model::build_model(scene);
  const std::size_t particles = model.particles.size();
  solver::SimLayout layout = solver::make_sim_layout(model);
  EnergyGrowthCheck energy_check(layout, xyz_of(plan::bytes_of(layout.v)), model.objects, sim.energy_growth_limit);
  solver::KinematicColliders colliders(model.colliders);  // posed per substep; the per-frame contact record
  std::optional<solver::SurfaceContactCheck> surfaces;    // the per-frame surface record
  if (model.contact_surface) surfaces.emplace(model.contact_surface->triangles, model.contact_surface->thickness);
  release_simulation_state(model);
  plan::SubstepPlan plan = with_stiffness_line(scene, [&] { return method.build(layout, settings); });
  layout = {};
  ExecutionOptions exec_options = execution_options(scene);
  exec_options.svm = svm_mode(options.svm_mode);
  Execution execution = during_set_up([&] { return prepare_execution(devices, std::move(plan), exec_options); });
  device::PlanExecutor* executor = execution.executor.get();
  if (g_stop) throw runtime_error(kInterruptedSetUp);

  const io::RunInfo info = run_info(options, scene, devices, execution, exec_options);
  io::Checkpoint resumed;
  io::ResultWriter writer(scene.output.path, info, model.objects, options.resume ? &resumed : nullptr);
  // A new choice at a frame boundary: its plan, profiled and scheduled,
  // continues from the state `now`.
  const auto switch_to = [&](const SolverChoice& choice, const plan::PlanState& now) {
    apply_choice(scene, choice);
    const solver::MethodDescription& m = solver::method(choice.method);
    const solver::MethodSettings s = solver::method_settings(scene, m);
    exec_options.mode = parse_schedule_mode(choice.schedule);
    execution = prepare_execution(devices, with_stiffness_line(scene, [&] { return m.build(tuning->layout(), s); }),
                                  exec_options);
    executor = execution.executor.get();
    executor->reset({now.positions, now.velocities, {}});  // (what another plan carried is not this one's)
    result.method = choice.method;
    result.schedule = choice.schedule;
  };
  const auto write_decisions = [&] {
    for (const DecisionEvent& e : tuning->take_events()) {
      // (No frame ran under the row before in this process: a resumed run
      // keeps what the file says.)
      if (!result.decisions.empty() && std::isfinite(e.previous_measured_ms)) {
        writer.set_decision_measured(e.previous_measured_ms);
        result.decisions.back().measured_ms = e.previous_measured_ms;
      }
      writer.append_decision(e.row);
      result.decisions.push_back(e.row);
    }
  };

  result.output_path = scene.output.path;
  result.xdmf_path = writer.xdmf_path();
  result.frames_requested = sim.frames;
  result.particles = particles;
  result.device = devices.info(0).name;
  result.method = scene.solver.method;
  result.schedule = info.schedule.mode;
  result.executor = info.schedule.executor;
  result.memory = info.schedule.memory;
  result.devices = info.devices;
  result.surface_contact = surfaces.has_value();
  if (tuning) {
    result.decisions = writer.decisions();  // those a resumed run kept
    if (options.resume) {
      // (A re-check's row is flushed with its frame's checkpoint, so the
      // rows kept are those an uninterrupted run had made by then.)
      const SolverChoice in_force = tuning->resume(writer.decisions(), static_cast<int>(resumed.frame));
      if (in_force.method != result.method || in_force.iterations != sim.iterations ||
          in_force.schedule != result.schedule) {
        switch_to(in_force, {resumed.positions, resumed.velocities, {}});
      }
    }
    write_decisions();
  }
  CrossingReport crossings(scene.contact.strict, options.warn);
  const auto record_contact = [&](int frame, const io::ContactFrame& c) {
    result.contact.push_back({frame, c});
    crossings.check(frame, c);
  };
  int first_frame = 1;
  if (options.resume) {
    const plan::PlanState fresh = executor->read_state();
    if (resumed.positions.size() != fresh.positions.size() || resumed.velocities.size() != fresh.velocities.size()) {
      throw input_error(
          fmt::format("--resume: the state in '{}' does not fit this scene's plan ({} bytes, the plan "
                      "has {}); run without --resume",
                      writer.path(), resumed.positions.size() + resumed.velocities.size(),
                      fresh.positions.size() + fresh.velocities.size()));
    }
    if (!resumed.carried.empty() && resumed.carried.size() != executor->carried_bytes()) {
      throw input_error(
          fmt::format("--resume: the state in '{}' carries {} bytes of contact lists' state, this scene's plan "
                      "{}; run without --resume",
                      writer.path(), resumed.carried.size(), executor->carried_bytes()));
    }
    if (resumed.frame >= sim.frames) {
      throw input_error(
          fmt::format("--resume: '{}' already holds {} simulated frames; pass --frames with more to "
                      "go on",
                      writer.path(), resumed.frame));
    }
    executor->reset({resumed.positions, resumed.velocities, resumed.carried});
    first_frame = static_cast<int>(resumed.frame) + 1;
    // The frames kept: in the summary, not reported again.
    const auto& kept = writer.resumed_contact();
    for (std::size_t row = 0; row < kept.size(); ++row)
      result.contact.push_back({static_cast<int>(row) * scene.output.stride, kept[row]});
  }
  plan::PlanState state = executor->read_state();
  std::vector<float> xyz = xyz_of(state.positions);
  const BlowUpBounds bounds =
      blow_up_bounds(xyz, xyz_of(state.velocities), std::hypot(sim.gravity[0], sim.gravity[1], sim.gravity[2]),
                     sim.frame_dt, sim.substeps);
  EnergyGrowthCheck::Energy energy = energy_check.energy(xyz, xyz_of(state.velocities));
  std::optional<io::ContactFrame> first_contact;
  if (!options.resume) {
    writer.set_checkpoint(0, state.positions, state.velocities, state.carried);
    first_contact = contact_frame(colliders, xyz, SurfaceMeasurement(surfaces, xyz).get());
    writer.append_frame(0.0, xyz, 0.0, 0.0, *first_contact);
  }
  result.frames_written = writer.frames_written();

  double total_ms = 0.0;
  std::vector<float> before;
  try {
    if (first_contact) record_contact(0, *first_contact);
    for (int frame = first_frame; frame <= sim.frames; ++frame) {
      if (g_stop) throw runtime_error(fmt::format("interrupted before frame {}", frame));
      injected_fault(frame);
      const auto start = std::chrono::steady_clock::now();
      run_frame(*executor, colliders, sim.substeps, frame, sim.frame_dt);
      before.swap(xyz);
      executor->read_positions(xyz);
      const bool written = frame % scene.output.stride == 0;
      SurfaceMeasurement surface_measurement = written ? SurfaceMeasurement(surfaces, xyz) : SurfaceMeasurement();
      const auto frame_end = std::chrono::steady_clock::now();
      const double ms = std::chrono::duration<double, std::milli>(frame_end - start).count();
      // Costs from this frame's profiling events refit the table; the
      // schedule follows (paper §5: re-profiled every frame with smoothing).
      const sched::Schedule used = execution.schedule;
      const std::vector<sched::Wait> used_waits = execution.waits;
      const std::vector<int> used_merge = execution.merge_group;
      const double used_unmerged_ms = execution.unmerged_makespan_ms;
      const auto schedule_start = std::chrono::steady_clock::now();
      const FrameMeasurement measured = refit_and_reschedule(execution, exec_options);
      const double schedule_ms =
          std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - schedule_start).count();
      std::optional<std::string> why = find_blow_up(before, xyz, bounds, frame * sim.frame_dt, 1);
      if (!why && energy_check.enabled()) {
        executor->read_state(state);
        EnergyGrowthCheck::Energy now = energy_check.energy(xyz, xyz_of(state.velocities));
        why = energy_check.check(energy, before, now, xyz);
        energy = std::move(now);
      }
      if (why) {
        throw runtime_error(
            fmt::format("frame {}: the simulation blew up ({}); use more substeps or iterations, "
                        "or softer materials",
                        frame, *why));
      }
      if (tuning) {
        // Re-checked on the state the frame ended in, before it is written,
        // so that its checkpoint and its /decisions row are flushed together.
        tuning->frame_done(ms);
        if (frame < sim.frames && tuning->due(frame)) {
          const plan::PlanState now = executor->read_state();
          if (const auto next = tuning->recheck(frame, now)) {
            switch_to(*next, now);
            executor->read_state(state);  // (the checkpoint's carried state is the new plan's)
          }
          write_decisions();
        }
      }
      const int done = frame - first_frame + 1;
      total_ms += ms;
      result.frames_simulated = frame;
      result.energy_growth = energy_check.largest_growth();
      result.frame_ms.push_back(ms);
      result.bytes_moved.push_back(static_cast<double>(measured.bytes_moved));
      result.mean_frame_ms = total_ms / done;
      if (written) {
        record_schedule(writer, frame, {used, used_waits, used_merge, used_unmerged_ms}, measured);
        if (!energy_check.enabled()) executor->read_state(state);
        writer.set_checkpoint(frame, state.positions, state.velocities, state.carried);
        const io::ContactFrame contact = contact_frame(colliders, xyz, surface_measurement.get());
        // The host's own work on the frame since it ended, less the
        // rescheduling: the checks, the state read, the surface record.
        const double host_ms =
            std::max(std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - frame_end).count() -
                         schedule_ms,
                     0.0);
        writer.append_frame(frame * sim.frame_dt, xyz, ms, schedule_ms, contact, host_ms);
        result.host_ms.push_back(host_ms);
        result.predicted_makespan_ms.push_back(used.makespan_ms);
        result.measured_makespan_ms.push_back(measured.makespan_ms);
        result.frames_written = writer.frames_written();
        record_contact(frame, contact);
      }
      result.frames_written = writer.frames_written();
      if (progress) progress({frame, sim.frames, ms, total_ms / done});
    }
  } catch (const std::exception& e) {  // atssim::Error included
    const int kept = writer.frames_written();
    writer.fail(e.what());
    const std::string where =
        writer.path() == writer.target_path()
            ? writer.path()
            : fmt::format("{}; the earlier {} was left as it was", writer.path(), writer.target_path());
    // The run failed after its output was created: an input error found this
    // late is the run's failure (exit 1, frames kept); a bug stays one.
    const ErrorKind kind = error_kind(e) == ErrorKind::internal ? ErrorKind::internal : ErrorKind::runtime;
    throw Error(fmt::format("{} ({} frames kept in {})", e.what(), kept, where), kind);
  }
  if (tuning && !result.decisions.empty() && std::isfinite(tuning->interval_ms())) {
    result.decisions.back().measured_ms = tuning->interval_ms();
    writer.set_decision_measured(result.decisions.back().measured_ms);
  }
  if (tuning && options.warn) {
    if (const auto why = tuning->budget_report()) options.warn(*why);
  }
  writer.finish();
  result.frames_written = writer.frames_written();
}

}  // namespace atssim::app
