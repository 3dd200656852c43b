#include "app/accuracy_control.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

#include <fmt/format.h>

#include "plan/buffer.hpp"
#include "sched/accuracy_choice.hpp"
#include "util/error.hpp"

namespace atssim::app {

namespace {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

double median(std::vector<double> v) {
  if (v.empty()) return kNaN;
  std::nth_element(v.begin(), v.begin() + static_cast<std::ptrdiff_t>((v.size() - 1) / 2), v.end());
  return v[(v.size() - 1) / 2];
}

}  // namespace

AccuracyControl::AccuracyControl(const scene::SceneDesc& scene, const device::DeviceSet& devices,
                                 const model::Model& model, std::function<void(const std::string&)> warn,
                                 double cost_scale)
    : scene_(scene),
      goal_{scene.solver.accuracy.tolerance, scene.solver.accuracy.budget_ms},
      probe_(scene, devices, cost_scale),
      layout_(solver::make_sim_layout(model)),
      warn_(std::move(warn)) {}

void AccuracyControl::record(int frame, double previous_y, double y_floor, bool changed, std::string reason) {
  io::DecisionRecord row;
  row.frame = frame;
  row.method = current_.method;
  row.iterations = current_.iterations;
  row.schedule = current_.schedule;
  row.y = current_.y;
  row.previous_y = previous_y;
  row.y_floor = y_floor;
  row.predicted_ms = current_.predicted_ms;
  row.check_ms = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - check_started_).count();
  row.changed = changed ? 1 : 0;
  row.reason = std::move(reason);
  events_.push_back({interval_ms(), row});
  interval_.clear();
}

SolverChoice AccuracyControl::start(const solver::SimLayout& state) {
  check_started_ = std::chrono::steady_clock::now();
  const ProbeTable table = probe_.probe(state, 0, kProbeSubsteps);
  if (!table.resolved) {
    // Nothing on the start state tells the choices apart (a body at rest or
    // in free fall): the scene's own settings — with a budget alone, as many
    // of its iterations as the budget holds — until a re-check finds a
    // state that does. Whether any choice fits a budget needs no y.
    resolved_ = false;
    const bool budget_alone = goal_.tolerance <= 0.0;
    if (budget_alone && !table.choice.chosen) throw input_error(none_meets_message(table, probe_.max_iterations()));
    if (table.scene_default) {
      current_ = table.at(*table.scene_default);
    } else {
      const std::string& method = probe_.methods().front();
      const int k = scene_.simulation.iterations;
      current_ = {method, k, "single", kNaN, probe_.predicted_ms(method, k, "single")};
    }
    if (budget_alone) {
      const int k = std::min(probe_.max_iterations(),
                             probe_.cost_line(current_.method, current_.schedule).most_within(goal_.budget_ms));
      if (k >= 1) {
        current_.iterations = k;
        current_.predicted_ms = probe_.predicted_ms(current_.method, k, current_.schedule);
        current_.y = kNaN;
      } else {
        current_ = table.at(*table.choice.chosen);
      }
    }
    record(0, kNaN, table.y_floor(), true,
           fmt::format("the start state does not resolve y to {:g} (float32 resolution {:.1e}): the scene's own "
                       "settings{}, re-checked every frame until a state does",
                       sched::resolution_needed(goal_), table.y_floor(),
                       budget_alone ? " with the iterations the budget holds" : ""));
    return current_;
  }
  if (!table.choice.chosen) throw input_error(none_meets_message(table, probe_.max_iterations()));
  current_ = table.at(*table.choice.chosen);
  record(0, kNaN, table.y_floor(), true,
         goal_.tolerance > 0.0 ? "probe: the cheapest choice that meets the tolerance"
                               : "probe: the most accurate choice within the budget");
  return current_;
}

SolverChoice AccuracyControl::resume(const std::vector<io::DecisionRecord>& kept, int frame) {
  const io::DecisionRecord* in_force = nullptr;
  for (const io::DecisionRecord& r : kept) {
    if (r.frame <= frame) in_force = &r;
  }
  if (in_force == nullptr) {
    throw input_error("--resume: the file records no choice of --tolerance / --budget; run without --resume");
  }
  current_ = {in_force->method, in_force->iterations, in_force->schedule, in_force->y, in_force->predicted_ms};
  // A state that resolved the goal was found when a row says so.
  resolved_ = std::any_of(kept.begin(), kept.end(), [&](const io::DecisionRecord& r) {
    return r.frame <= frame && sched::resolves(r.y_floor, sched::resolution_needed(goal_));
  });
  return current_;
}

void AccuracyControl::frame_done(double frame_ms) {
  interval_.push_back(frame_ms);
  frames_.push_back(frame_ms);
}

std::optional<std::string> AccuracyControl::budget_report() {
  if (goal_.tolerance > 0.0 || !(goal_.budget_ms > 0.0)) return std::nullopt;
  const double ms = median(frames_);
  const int most = probe_.max_iterations();
  const std::string head = fmt::format("the median frame took {:.3g} ms against a budget of {:g} ms ({:+.0f} %)", ms,
                                       goal_.budget_ms, 100.0 * (ms / goal_.budget_ms - 1.0));
  // One iteration more, predicted by the cost line scaled to what was measured.
  // (NaN where the probe has no line for the choice, e.g. one resumed from a
  // run on other devices.)
  double next_ms = kNaN;
  if (current_.predicted_ms > 0.0 && probe_.has_cost_line(current_.method, current_.schedule)) {
    next_ms =
        probe_.cost_line(current_.method, current_.schedule).at(current_.iterations + 1) * ms / current_.predicted_ms;
  }
  switch (sched::budget_miss(goal_.budget_ms, ms, current_.iterations, most, 0.1, next_ms)) {
    case sched::BudgetMiss::none:
      return std::nullopt;
    case sched::BudgetMiss::too_small:
      return fmt::format(
          "{}: at one iteration of {}, the least, what a frame costs besides the iterations (predict, contact, "
          "{} substeps) is above the budget; raise --budget or lower simulation.substeps",
          head, current_.method, scene_.simulation.substeps);
    case sched::BudgetMiss::too_large:
      return fmt::format("{}: {} iterations of {}, the most the probe tries, take less; no choice needs the budget",
                         head, most, current_.method);
    case sched::BudgetMiss::granular:
      return fmt::format(
          "{}: {} {} of {} {} the most that fit; {} would take about {:.3g} ms, over the budget (iterations "
          "come in whole steps of about {:.2g} ms a frame here); a budget of {:.3g} ms or more allows them",
          head, current_.iterations, current_.iterations == 1 ? "iteration" : "iterations", current_.method,
          current_.iterations == 1 ? "is" : "are", current_.iterations + 1, next_ms, next_ms - ms, next_ms);
    case sched::BudgetMiss::unsettled:
      break;
  }
  return fmt::format(
      "{}: the frame time moved between re-checks (other load on the devices) or the run ended before one; "
      "a shorter --recheck follows it closer",
      head);
}

double AccuracyControl::interval_ms() const { return median(interval_); }

bool AccuracyControl::due(int frame) const {
  const int every = scene_.solver.accuracy.recheck;
  if (every <= 0) return false;
  if (!resolved_) return true;
  if (goal_.tolerance <= 0.0 && frame == kBudgetCalibrationFrame && frame < every) return true;
  return frame % every == 0;
}

std::optional<SolverChoice> AccuracyControl::recheck(int frame, const plan::PlanState& state) {
  check_started_ = std::chrono::steady_clock::now();
  layout_.x = plan::values_of<solver::Float4>(state.positions);
  layout_.v = plan::values_of<solver::Float4>(state.velocities);
  ProbedState measured;
  // A budget's re-check, once a state has resolved y (and the probe has
  // ranked the choices by it), decides by the measured frame time alone: it
  // computes no Newton reference (most of a re-check's time, 17-137 s each
  // on the soft box under load) and records y and y_floor as NaN.
  const bool by_time = goal_.tolerance <= 0.0 && resolved_;
  if (by_time) measured.y_floor = kNaN;
  // Until a state resolves the tolerance, y is measured only on one that
  // does (elsewhere it is float32 rounding, and the choice stays).
  const double y =
      by_time ? kNaN
              : probe_.measure(current_, layout_, frame, &measured, resolved_ ? 0.0 : sched::resolution_needed(goal_));
  const double measured_ms = interval_ms();
  const bool resolves = by_time || sched::resolves(measured.y_floor, sched::resolution_needed(goal_));
  const SolverChoice before = current_;
  if (!resolved_ && !resolves) {
    current_.y = y;
    record(
        frame, y, measured.y_floor, false,
        fmt::format("the state does not resolve y to the tolerance yet (float32 resolution {:.1e})", measured.y_floor));
    return std::nullopt;
  }
  // The first state that resolves the tolerance gets the whole probe.
  const bool resolved_before = resolved_;
  const sched::Recheck verdict =
      !resolved_ ? sched::Recheck::reprobe : sched::recheck_verdict(goal_, y, resolves, measured_ms);
  resolved_ = true;
  std::string reason;
  if (verdict == sched::Recheck::keep) {
    current_.y = y;
    record(frame, y, measured.y_floor, false,
           goal_.tolerance > 0.0 ? fmt::format("kept: y {:.2e} within the tolerance", y)
                                 : fmt::format("kept: {:.3g} ms per frame within 10 % of the budget", measured_ms));
    return std::nullopt;
  }
  if (verdict == sched::Recheck::reprobe) {
    const ProbeTable table = probe_.probe(layout_, frame, 1);
    const std::string why = resolved_before ? fmt::format("y {:.2e} above the tolerance", y)
                                            : std::string("the first state that resolves y");
    if (table.choice.chosen) {
      current_ = table.at(*table.choice.chosen);
      reason = why + (goal_.tolerance > 0.0 ? ": probed, the cheapest choice that meets the tolerance"
                                            : ": probed, the most accurate choice within the budget");
    } else {
      current_ = table.choice.nearest.empty() ? current_ : table.at(table.choice.nearest.front());
      reason = why + ", and no choice meets it here: the most accurate";
      if (!warned_none_ && warn_)
        warn_(fmt::format("frame {}: {}", frame, none_meets_message(table, probe_.max_iterations())));
      warned_none_ = true;
    }
  } else {
    const sched::IterationCost line = probe_.cost_line(current_.method, current_.schedule);
    const int k = std::min(probe_.max_iterations(),
                           sched::iterations_for_budget(line, current_.predicted_ms, measured_ms, goal_.budget_ms));
    reason = fmt::format("{:.3g} ms per frame measured against a budget of {:g}: {} iterations", measured_ms,
                         goal_.budget_ms, k);
    if (k != current_.iterations) {
      current_.iterations = k;
      current_.predicted_ms = line.at(k);
    }
    current_.y = y;  // NaN: a budget's re-check measures no y (above)
  }
  const bool changed = !current_.same_as(before);
  record(frame, y, measured.y_floor, changed, reason);
  return changed ? std::optional<SolverChoice>(current_) : std::nullopt;
}

std::vector<DecisionEvent> AccuracyControl::take_events() {
  std::vector<DecisionEvent> out;
  out.swap(events_);
  return out;
}

}  // namespace atssim::app
