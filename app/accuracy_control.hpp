#pragma once
// How a run with a tolerance or a budget keeps its choice (docs/accuracy.md,
// "Accuracy as the input"): the probe before frame 1; a re-check on the live
// state every solver.recheck frames (and every frame while no state has yet
// resolved the tolerance; for a budget alone, once more after frame 3); a
// /decisions row for each. The verdicts are sched::recheck_verdict's and
// the choices sched::choose_accuracy's; this class keeps the state between.
#include <chrono>
#include <functional>
#include <optional>
#include <string>
#include <vector>

#include "app/accuracy_probe.hpp"
#include "io/decision_series.hpp"
#include "plan/plan_state.hpp"

namespace atssim::app {

// A row of /decisions, and the measured frame time of the row before it
// (the median of its frames; NaN when it had none).
struct DecisionEvent {
  double previous_measured_ms = 0.0;
  io::DecisionRecord row;
};

class AccuracyControl {
 public:
  // Probe states before frame 1: the start state and those after exact
  // substeps from it.
  static constexpr int kProbeSubsteps = 3;
  // With a budget alone: a first re-check of the frame time after this frame.
  static constexpr int kBudgetCalibrationFrame = 3;

  // `cost_scale` > 0: the cost model's ms per µs instead of a profile (AccuracyProbe).
  AccuracyControl(const scene::SceneDesc& scene, const device::DeviceSet& devices, const model::Model& model,
                  std::function<void(const std::string&)> warn, double cost_scale = 0.0);

  // The choice for frame 1 on, from the probe of the start state. Throws
  // atssim::Error (input) when no choice meets the goal.
  SolverChoice start(const solver::SimLayout& state);
  // A resumed run: the choice in force at `frame` by the rows the file kept
  // (the probe is not run again: an uninterrupted run would not have).
  SolverChoice resume(const std::vector<io::DecisionRecord>& kept, int frame);

  // A frame ran in `frame_ms` of wall time.
  void frame_done(double frame_ms);
  // Whether the state after `frame` is re-checked (the caller reads it only then).
  bool due(int frame) const;
  // Re-checks on the state after `frame`; the new choice when it changed.
  std::optional<SolverChoice> recheck(int frame, const plan::PlanState& state);

  // The rows made since the last call.
  std::vector<DecisionEvent> take_events();
  // The median frame time since the last row (NaN: no frame yet).
  double interval_ms() const;
  // With a budget alone, when the median frame of the run (of this process)
  // is off the budget by more than 10 %: one line saying so and why. Empty
  // otherwise.
  std::optional<std::string> budget_report();
  const SolverChoice& current() const { return current_; }
  AccuracyProbe& probe() { return probe_; }
  // The start layout with the state of the last re-check (the plans of a
  // new choice are built from it).
  const solver::SimLayout& layout() const { return layout_; }

 private:
  void record(int frame, double previous_y, double y_floor, bool changed, std::string reason);

  scene::SceneDesc scene_;
  sched::AccuracyGoal goal_;
  AccuracyProbe probe_;
  solver::SimLayout layout_;  // the start layout; x and v replaced by the live state at a re-check
  std::function<void(const std::string&)> warn_;
  SolverChoice current_;
  bool resolved_ = true;  // whether a state resolved the tolerance yet (false: the scene's own settings meanwhile)
  bool warned_none_ = false;
  std::vector<double> interval_;  // frame times since the last row
  std::vector<double> frames_;    // every frame time of this process
  std::chrono::steady_clock::time_point check_started_;
  std::vector<DecisionEvent> events_;
};

}  // namespace atssim::app
