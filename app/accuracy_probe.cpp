#include "app/accuracy_probe.hpp"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <limits>
#include <map>
#include <tuple>

#include <fmt/format.h>

#include "app/execution.hpp"
#include "app/scene_checks.hpp"
#include "device/executor_choice.hpp"
#include "device/plan_executor.hpp"
#include "model/cloth_builder.hpp"
#include "plan/task_work.hpp"
#include "solver/contact/kinematic_colliders.hpp"
#include "solver/method_registry.hpp"
#include "solver/newton/substep_reference.hpp"
#include "util/error.hpp"

namespace atssim::app {

namespace {

using solver::Float4;
constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();
constexpr int kMaxIterations = 1024;

// A fixed cost of every hop between tasks on one device, and of a wait
// across devices, in µs of the reference device (fused: an SVM counter;
// events: a launch and an event).
struct HopCosts {
  double task_us = 1.5;
  double wait_us = 2.0;
};

HopCosts hop_costs(device::ExecutorKind kind) {
  if (kind == device::ExecutorKind::events) return {10.0, 25.0};
  return {};
}

// The scene as if it named `method` (its solver.method line then names
// where the method came from, for messages).
scene::SceneDesc scene_with_method(const scene::SceneDesc& scene, const solver::MethodDescription& method,
                                   const std::string& where) {
  scene::SceneDesc s = scene;
  s.solver.method = std::string(method.name);
  s.solver.method_where = where;
  return s;
}

// The scene without friction: y measures how well the iterations solve the
// incremental potential, and friction (a step after the iterations, on
// the substep's displacement) is no part of it — with friction every
// method's y would stop at what friction moves (4e-2 on the drape).
scene::SceneDesc without_friction(scene::SceneDesc s) {
  for (scene::ColliderDesc& c : s.colliders) {
    c.static_friction = c.kinetic_friction = 0.0;
    c.friction_set = true;
  }
  for (scene::ObjectDesc& o : s.objects) o.material.has_friction = false;
  s.contact.static_friction = s.contact.kinetic_friction = 0.0;
  return s;
}

}  // namespace

struct AccuracyProbe::Impl {
  scene::SceneDesc scene;
  const device::DeviceSet& devices;
  solver::SimLayout base;  // the start layout the plans are built from (x, v replaced when they run)
  solver::KinematicColliders colliders;
  double h = 0.0;
  int substeps = 1;
  std::vector<const solver::MethodDescription*> methods;
  std::vector<std::string> names;
  std::vector<std::string> schedules;
  std::vector<std::vector<int>> method_schedules;  // per method: the schedules it may run on
  device::ExecutorOptions executor;                // measures y
  device::ExecutorOptions calibration;             // profiles the cost model's scale
  HopCosts hops;
  std::vector<double> ms_per_us;  // per device, once calibrated
  std::map<std::pair<int, int>, sched::IterationCost> lines;
  std::unique_ptr<device::PlanExecutor> last;  // the executor measure_y ran last, and its method and iterations
  std::pair<int, int> last_key{-1, 0};

  Impl(const scene::SceneDesc& s, const device::DeviceSet& d) : scene(without_friction(s)), devices(d) {
    const model::Model model = model::build_model(scene);
    base = solver::make_sim_layout(model);
    colliders = solver::KinematicColliders(model.colliders);
    h = scene.simulation.frame_dt / scene.simulation.substeps;
    substeps = scene.simulation.substeps;
    const ExecutionOptions e = execution_options(scene);
    // Calibrated on the executor the run uses; y measured on the events
    // executor, which gives the same bits (device/plan_executor.hpp) and is
    // built in about half the time of a fused one (the probe builds one
    // per method and iteration count).
    calibration.kind = e.executor;
    calibration.wait_timeout_s = e.wait_timeout_s;
    executor.kind = device::ExecutorKind::events;
    hops = hop_costs(device::choose_executor(e.executor, devices.infos(), devices.memories()));
    choose_schedules();
    choose_methods();
  }

  void choose_schedules() {
    if (!scene.solver.schedule_where.empty()) {
      if (scene.solver.schedule == "async") {
        throw input_error(fmt::format(
            "{}: schedule async does not go with a tolerance or a budget: its result depends on the devices' "
            "timing, so its error cannot be chosen ahead; use single, split or heft, or leave the schedule to atssim",
            scene.solver.schedule_where));
      }
      schedules = {scene.solver.schedule};
    } else {
      schedules = {"single"};
      if (devices.size() >= 2) schedules.insert(schedules.end(), {"split", "heft"});
    }
  }

  plan::SubstepPlan build(const solver::MethodDescription& m, int iterations) const {
    const scene::SceneDesc s = scene_with_method(scene, m, scene.solver.accuracy.methods_where);
    solver::MethodSettings settings = solver::method_settings(s, m);
    settings.iterations = iterations;
    return with_stiffness_line(s, [&] { return m.build(base, settings); });
  }

  // Whether `m` can take part: the scene allows it (solids, colliders,
  // options, finite stiffness), it has iterations to choose, and it runs
  // on one of the schedules. Listed methods that cannot are input errors.
  bool admit(const solver::MethodDescription& m, bool listed) {
    const std::string& where = scene.solver.accuracy.methods_where;
    std::vector<int> allowed;
    try {
      solver::check_scene(scene_with_method(scene, m, where), m);
      const plan::SubstepPlan one = build(m, 1), two = build(m, 2);
      if (one.graph.size() == two.graph.size()) {
        if (!listed) return false;
        throw input_error(
            fmt::format("{}: {} has no iterations to choose (it is not an iterative method); list "
                        "iterative methods only (atssim methods)",
                        where, m.name));
      }
      for (std::size_t i = 0; i < schedules.size(); ++i) {
        if (schedules[i] == "single" || one.one_device_reason.empty()) allowed.push_back(static_cast<int>(i));
      }
      if (allowed.empty()) {
        if (!listed) return false;
        throw input_error(fmt::format("{}: {} runs on one device only ({}), and the schedule is {}", where, m.name,
                                      one.one_device_reason, schedules.front()));
      }
    } catch (const Error& e) {
      if (listed || e.kind() != ErrorKind::input) throw;
      return false;
    }
    methods.push_back(&m);
    names.emplace_back(m.name);
    method_schedules.push_back(std::move(allowed));
    return true;
  }

  void choose_methods() {
    const auto& listed = scene.solver.accuracy.methods;
    if (!listed.empty()) {
      for (const std::string& name : listed) {
        const solver::MethodDescription& m = solver::method(name, scene.solver.accuracy.methods_where);
        if (std::find(names.begin(), names.end(), name) == names.end()) admit(m, true);
      }
      return;
    }
    for (const solver::MethodDescription* m : solver::methods()) admit(*m, false);
    if (methods.empty()) {
      throw input_error(
          "no method this scene allows has iterations to choose, so a tolerance or a budget has nothing to "
          "choose; drop solver.tolerance and solver.budget_ms");
    }
  }

  // ms per µs of the reference device, per device: the profiled cost of the
  // first method's plan on each device against the model's, task by task;
  // the median ratio weighted by the modelled cost, so that a task the
  // machine's load held back does not scale the rest. Devices that are alike
  // (name, type, compute units) share their mean, so that the ranking of
  // schedules on two halves of one device does not follow noise.
  void calibrate() {
    if (!ms_per_us.empty()) return;
    const plan::SubstepPlan plan = build(*methods.front(), std::min(8, scene.simulation.iterations));
    device::PlanExecutor probe(devices, plan, calibration);
    const sched::CostTable measured = profile(probe, 3);
    const std::size_t n = devices.size();
    std::vector<double> scale(n, 1e-3);
    for (std::size_t d = 0; d < n; ++d) {
      std::vector<std::pair<double, double>> ratios;  // measured / modelled, modelled
      double total = 0.0;
      for (sched::TaskId t = 0; t < measured.tasks; ++t) {
        const double model_us = plan::task_work_us(plan, t, {hops.task_us});
        if (!std::isfinite(measured.at(t, d)) || measured.at(t, d) <= 0.0 || model_us <= 0.0) continue;
        ratios.emplace_back(measured.at(t, d) / model_us, model_us);
        total += model_us;
      }
      std::sort(ratios.begin(), ratios.end());
      double seen = 0.0;
      for (const auto& [ratio, weight] : ratios) {
        seen += weight;
        if (seen >= 0.5 * total) {
          scale[d] = ratio;
          break;
        }
      }
    }
    ms_per_us.assign(n, 0.0);
    const auto& infos = devices.infos();
    for (std::size_t d = 0; d < n; ++d) {
      double sum = 0.0;
      int alike = 0;
      for (std::size_t e = 0; e < n; ++e) {
        if (infos[e].name == infos[d].name && infos[e].type == infos[d].type &&
            infos[e].compute_units == infos[d].compute_units) {
          sum += scale[e];
          ++alike;
        }
      }
      ms_per_us[d] = sum / alike;
    }
  }

  double frame_ms(const plan::SubstepPlan& plan, const std::string& schedule) {
    calibrate();
    const ScheduleMode mode = parse_schedule_mode(schedule);
    const plan::SubstepPlan cut = cut_for_mode(plan, mode, devices.size());
    const sched::CostTable costs = plan::work_cost_table(cut, ms_per_us, {hops.task_us});
    double mean = 0.0;
    for (double s : ms_per_us) mean += s / static_cast<double>(ms_per_us.size());
    const PlannedSchedule p = schedule_from_costs(plan, mode, costs, hops.wait_us * mean);
    return p.schedule.makespan_ms * substeps;
  }

  sched::IterationCost line(int method, int schedule) {
    const auto key = std::make_pair(method, schedule);
    if (const auto it = lines.find(key); it != lines.end()) return it->second;
    const solver::MethodDescription& m = *methods[method];
    const sched::IterationCost c = sched::IterationCost::from_two(frame_ms(build(m, 1), schedules[schedule]),
                                                                  frame_ms(build(m, 2), schedules[schedule]));
    lines.emplace(key, c);
    return c;
  }

  // The states and references last made, and what they were made from: a
  // re-check and the probe that follows it on the same state share them
  // (the Newton reference is most of a re-check's time).
  struct MadeStates {
    int frame = -1;
    std::vector<Float4> x, v;
    std::vector<solver::SimLayout> states;
    std::vector<solver::newton::SubstepReference> references;
  } made;

  // The probed states: `state`, then each after the exact substep from the
  // one before; the colliders where they are during each.
  void make_states(const solver::SimLayout& state, int frame, int count, std::vector<solver::SimLayout>& states,
                   std::vector<solver::newton::SubstepReference>& references) {
    const auto same_bits = [](const std::vector<Float4>& a, const std::vector<Float4>& b) {
      return a.size() == b.size() && std::memcmp(a.data(), b.data(), a.size() * sizeof(Float4)) == 0;
    };
    const bool same = made.frame == frame && same_bits(made.x, state.x) && same_bits(made.v, state.v);
    if (!same) made = {frame, state.x, state.v, {}, {}};
    const std::size_t reuse = std::min<std::size_t>(made.states.size(), static_cast<std::size_t>(count));
    states.assign(made.states.begin(), made.states.begin() + static_cast<std::ptrdiff_t>(reuse));
    references.assign(made.references.begin(), made.references.begin() + static_cast<std::ptrdiff_t>(reuse));
    const double t = frame * scene.simulation.frame_dt;
    for (int i = static_cast<int>(reuse); i < count; ++i) {
      solver::SimLayout s = i == 0 ? state : solver::newton::exact_step(states.back(), references.back());
      // The probe's own colliders and particle friction (none), posed for
      // the substep.
      s.friction = base.friction;
      s.colliders = colliders.moving() ? colliders.records(t + i * h, t + (i + 1) * h) : base.colliders;
      references.push_back(solver::newton::substep_reference(s, h));
      states.push_back(std::move(s));
    }
    if (states.size() > made.states.size()) {
      made.states = states;
      made.references = references;
    }
  }

  // y of `method` at `iterations`: the worst over the states in `counted`.
  double measure_y(int method, int iterations, const std::vector<solver::SimLayout>& states,
                   const std::vector<solver::newton::SubstepReference>& references,
                   const std::vector<std::size_t>& counted) {
    if (counted.empty()) return 0.0;  // nothing to solve on any state
    // The last plan's executor is kept: a re-check measures the same choice
    // again (building one costs more than a small scene's substep).
    if (!last || last_key != std::make_pair(method, iterations)) {
      last.reset();
      last = std::make_unique<device::PlanExecutor>(devices, build(*methods[method], iterations), executor);
      last_key = {method, iterations};
    }
    device::PlanExecutor& run = *last;
    const plan::BufferId collider_buffer = run.plan().find_buffer(plan::BufferRole::colliders);
    double worst = 0.0;
    for (std::size_t s : counted) {
      run.reset({plan::bytes_of(states[s].x), plan::bytes_of(states[s].v), {}});
      if (colliders.moving() && collider_buffer >= 0) {
        run.write(collider_buffer, std::as_bytes(std::span(states[s].colliders)));
      }
      run.run_substeps(1);
      const std::vector<Float4> x = plan::values_of<Float4>(run.read_state().positions);
      const double y = references[s].relative_error(states[s], x);
      worst = std::isfinite(y) ? std::max(worst, y) : kNaN;
      if (!std::isfinite(worst)) break;
    }
    return worst;
  }

  int index_of(const std::string& name) const {
    const auto it = std::find(names.begin(), names.end(), name);
    return it == names.end() ? -1 : static_cast<int>(it - names.begin());
  }
};

SolverChoice ProbeTable::at(std::size_t candidate) const {
  const sched::AccuracyCandidate& c = candidates.at(candidate);
  return {methods[c.method], c.iterations, schedules[c.schedule], c.y, c.predicted_ms};
}

double ProbeTable::y_floor() const {
  double worst = 0.0;
  for (const ProbedState& s : states) worst = std::max(worst, std::isfinite(s.y_floor) ? s.y_floor : 0.0);
  return worst;
}

AccuracyProbe::AccuracyProbe(const scene::SceneDesc& scene, const device::DeviceSet& devices, double ms_per_us)
    : impl_(std::make_unique<Impl>(scene, devices)) {
  if (ms_per_us > 0.0) impl_->ms_per_us.assign(devices.size(), ms_per_us);
}

AccuracyProbe::~AccuracyProbe() = default;

const std::vector<std::string>& AccuracyProbe::methods() const { return impl_->names; }
int AccuracyProbe::max_iterations() const { return kMaxIterations; }

sched::IterationCost AccuracyProbe::cost_line(const std::string& method, const std::string& schedule) {
  const int m = impl_->index_of(method);
  const auto s = std::find(impl_->schedules.begin(), impl_->schedules.end(), schedule);
  if (m < 0 || s == impl_->schedules.end()) {
    throw runtime_error(fmt::format("internal error: no cost line for {} on {}", method, schedule));
  }
  return impl_->line(m, static_cast<int>(s - impl_->schedules.begin()));
}

bool AccuracyProbe::has_cost_line(const std::string& method, const std::string& schedule) const {
  return impl_->index_of(method) >= 0 &&
         std::find(impl_->schedules.begin(), impl_->schedules.end(), schedule) != impl_->schedules.end();
}

double AccuracyProbe::predicted_ms(const std::string& method, int iterations, const std::string& schedule) {
  return cost_line(method, schedule).at(iterations);
}

double AccuracyProbe::measure(const SolverChoice& choice, const solver::SimLayout& state, int frame,
                              ProbedState* measured, double resolution) {
  Impl& p = *impl_;
  std::vector<solver::SimLayout> states;
  std::vector<solver::newton::SubstepReference> references;
  p.make_states(state, frame, 1, states, references);
  const double span = references[0].span();
  if (measured) *measured = {frame, 0, span, references[0].y_floor};
  const int m = p.index_of(choice.method);
  if (m < 0) throw runtime_error(fmt::format("internal error: {} is no candidate method", choice.method));
  if (resolution > 0.0 && !sched::resolves(references[0].y_floor, resolution)) return kNaN;
  return p.measure_y(m, choice.iterations, states, references,
                     span > 0.0 ? std::vector<std::size_t>{0} : std::vector<std::size_t>{});
}

ProbeTable AccuracyProbe::probe(const solver::SimLayout& state, int frame, int substeps) {
  Impl& p = *impl_;
  ProbeTable t;
  t.goal = {p.scene.solver.accuracy.tolerance, p.scene.solver.accuracy.budget_ms};
  t.methods = p.names;
  t.schedules = p.schedules;
  std::vector<solver::SimLayout> states;
  std::vector<solver::newton::SubstepReference> references;
  p.make_states(state, frame, std::max(1, substeps), states, references);

  // The states y is taken over: those that resolve the goal
  // (sched::resolution_needed), else every state with something to solve.
  std::vector<std::size_t> counted, solvable;
  for (std::size_t s = 0; s < states.size(); ++s) {
    t.states.push_back({frame, static_cast<int>(s), references[s].span(), references[s].y_floor});
    if (references[s].span() <= 0.0) continue;
    solvable.push_back(s);
    if (sched::resolves(references[s].y_floor, sched::resolution_needed(t.goal))) counted.push_back(s);
  }
  t.resolved = !counted.empty();
  if (counted.empty()) counted = solvable;

  const auto add_rows = [&](int m, int k, double y) {
    for (int s : p.method_schedules[m]) t.candidates.push_back({m, k, s, y, p.line(m, s).at(k)});
  };
  const auto cheapest = [&](int m, int k) {
    double best = std::numeric_limits<double>::infinity();
    for (int s : p.method_schedules[m]) best = std::min(best, p.line(m, s).at(k));
    return best;
  };
  const bool tolerance = t.goal.tolerance > 0.0, budget = t.goal.budget_ms > 0.0;
  // No state tells the choices apart: only the scene's own settings are
  // measured (a run keeps them, with as many iterations as a budget holds,
  // until a state does), and with a budget the cheapest choice (whether
  // any fits does not depend on y).
  const std::vector<int> ladder =
      t.resolved ? sched::iteration_ladder(kMaxIterations, p.scene.simulation.iterations) : std::vector<int>{1};
  // Every method and iteration count in the order of their predicted time
  // (ties: the methods' order, then fewer iterations): with a tolerance the
  // first that meets it is the cheapest, so the probe stops there — nothing
  // dearer is run (y need not fall with more iterations, so no method's
  // ladder can stop early on its own); with a budget, what fits.
  std::vector<std::tuple<double, int, int>> order;
  for (int m = 0; m < static_cast<int>(p.methods.size()); ++m) {
    for (int k : ladder) order.emplace_back(cheapest(m, k), m, k);
  }
  std::sort(order.begin(), order.end());
  if (!t.resolved) order.resize(budget ? std::min<std::size_t>(order.size(), 1) : 0);
  double best_meeting = std::numeric_limits<double>::infinity();
  for (const auto& [cost, m, k] : order) {
    // (The cheapest is measured even over the budget: it is the nearest.)
    if ((tolerance && cost > best_meeting) || (budget && cost > t.goal.budget_ms && !t.candidates.empty())) break;
    const double y = p.measure_y(m, k, states, references, counted);
    add_rows(m, k, y);
    if (tolerance && y <= t.goal.tolerance) best_meeting = std::min(best_meeting, cost);
  }
  // The scene's own settings, measured when the ladder stopped before them.
  const int own = p.index_of(p.scene.solver.method);
  const std::string own_schedule = p.scene.solver.schedule_where.empty() ? "single" : p.scene.solver.schedule;
  const auto own_schedule_at = std::find(p.schedules.begin(), p.schedules.end(), own_schedule);
  if (own >= 0 && own_schedule_at != p.schedules.end()) {
    const int k = p.scene.simulation.iterations, s = static_cast<int>(own_schedule_at - p.schedules.begin());
    const auto find_own = [&] {
      for (std::size_t i = 0; i < t.candidates.size(); ++i) {
        const auto& c = t.candidates[i];
        if (c.method == own && c.iterations == k && c.schedule == s) return std::optional<std::size_t>(i);
      }
      return std::optional<std::size_t>();
    };
    if (!find_own() && k <= kMaxIterations) add_rows(own, k, p.measure_y(own, k, states, references, counted));
    t.scene_default = find_own();
  }
  t.choice = sched::choose_accuracy(t.candidates, t.goal);
  // A budget alone: the chosen method and schedule with as many iterations
  // as the budget holds, when that is more accurate still.
  if (budget && !tolerance && t.choice.chosen && t.resolved) {
    const sched::AccuracyCandidate c = t.candidates[*t.choice.chosen];
    const int fill = std::min(kMaxIterations, p.line(c.method, c.schedule).most_within(t.goal.budget_ms));
    if (fill > c.iterations) {
      const double y = p.measure_y(c.method, fill, states, references, counted);
      t.candidates.push_back({c.method, fill, c.schedule, y, p.line(c.method, c.schedule).at(fill)});
      t.choice = sched::choose_accuracy(t.candidates, t.goal);
    }
  }
  return t;
}

std::string format_probe_table(const ProbeTable& t) {
  std::string out =
      fmt::format("probe: {} state{} from frame {}; y = (E - E*)/(E0 - E*), float32 resolution {:.1e}", t.states.size(),
                  t.states.size() == 1 ? "" : "s", t.states.empty() ? 0 : t.states.front().frame, t.y_floor());
  if (t.goal.tolerance > 0.0) out += fmt::format("; tolerance {:g}", t.goal.tolerance);
  if (t.goal.budget_ms > 0.0) out += fmt::format("; budget {:g} ms per frame", t.goal.budget_ms);
  if (!t.resolved) out += " (no state resolves y to that: its values are float32 rounding)";
  out += fmt::format("\n{:<8} {:>10} {:>10}", "method", "iterations", "y");
  for (const std::string& s : t.schedules) out += fmt::format(" {:>12}", s + " ms");
  out += "\n";
  // One row per method and iteration count, in the order probed.
  std::vector<std::pair<int, int>> rows;
  for (const auto& c : t.candidates) {
    if (std::find(rows.begin(), rows.end(), std::make_pair(c.method, c.iterations)) == rows.end())
      rows.emplace_back(c.method, c.iterations);
  }
  std::stable_sort(rows.begin(), rows.end());
  for (const auto& [m, k] : rows) {
    std::vector<std::string> cells(t.schedules.size(), "-");
    double y = kNaN;
    std::string mark;
    for (std::size_t i = 0; i < t.candidates.size(); ++i) {
      const auto& c = t.candidates[i];
      if (c.method != m || c.iterations != k) continue;
      y = c.y;
      cells[c.schedule] = fmt::format("{:.3f}", c.predicted_ms);
      if (t.choice.chosen == i) cells[c.schedule] += "*";
      if (t.scene_default == i) mark = "  (the scene's own)";
    }
    out += fmt::format("{:<8} {:>10} {:>10.2e}", t.methods[m], k, y);
    for (const std::string& cell : cells) out += fmt::format(" {:>12}", cell);
    out += mark + "\n";
  }
  if (t.choice.chosen) {
    const SolverChoice c = t.at(*t.choice.chosen);
    out += fmt::format("chosen (*): {} at {} iterations on {}: y {:.2e}, {:.3f} ms per frame predicted\n", c.method,
                       c.iterations, c.schedule, c.y, c.predicted_ms);
  }
  return out;
}

std::string none_meets_message(const ProbeTable& t, int max_iterations) {
  const bool tolerance = t.goal.tolerance > 0.0;
  std::string want;
  if (tolerance) want = fmt::format("reaches y <= {:g}", t.goal.tolerance);
  if (t.goal.budget_ms > 0.0) {
    want += fmt::format("{}fits {:g} ms per frame", tolerance ? " and " : "", t.goal.budget_ms);
  }
  std::string nearest;
  for (std::size_t i : t.choice.nearest) {
    const SolverChoice c = t.at(i);
    nearest += fmt::format("{}{} at {} iterations on {} (y {:.2e}, {:.3g} ms per frame)", nearest.empty() ? "" : ", ",
                           c.method, c.iterations, c.schedule, c.y, c.predicted_ms);
  }
  const int frame = t.states.empty() ? 0 : t.states.front().frame;
  return fmt::format("no choice {} on {} (methods {}, up to {} iterations); the nearest: {}; {}", want,
                     frame == 0 ? "the start state" : fmt::format("the state of frame {}", frame),
                     fmt::join(t.methods, ", "), max_iterations, nearest.empty() ? "none" : nearest,
                     tolerance ? "raise the tolerance (or the budget), or list other solver.methods"
                               : "raise the budget, or use fewer substeps");
}

}  // namespace atssim::app
