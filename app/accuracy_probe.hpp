#pragma once
// The probe of `run --tolerance` / `--budget` and `schedule --tolerance`
// (docs/accuracy.md, "Accuracy as the input"). From a state, every method
// the scene allows runs one substep at a ladder of iteration counts on the
// run's devices; the relative energy error y of each result is measured
// against the Newton reference (solver/newton/substep_reference), over a
// few states (the state and those after exact substeps from it; friction
// off, as it is no part of that potential), and the
// cost model (plan/task_work) predicts each choice's frame time on each
// schedule. sched::choose_accuracy then picks. The probe runs the plans;
// it decides nothing itself.
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "device/device_set.hpp"
#include "scene/scene_desc.hpp"
#include "sched/accuracy_choice.hpp"
#include "solver/layout/sim_layout.hpp"

namespace atssim::app {

// A choice of how to solve: what runs, and what was measured and predicted.
struct SolverChoice {
  std::string method;
  int iterations = 0;
  std::string schedule;  // single, split or heft
  double y = 0.0;        // on the probed states (NaN: not measured)
  double predicted_ms = 0.0;

  bool same_as(const SolverChoice& other) const {
    return method == other.method && iterations == other.iterations && schedule == other.schedule;
  }
};

// One probed state: its frame and what the reference measured on it.
struct ProbedState {
  int frame = 0;      // the run's frame it starts from (0: the initial state)
  int substep = 0;    // exact substeps after that frame's end
  double span = 0.0;  // E_0 − E*
  double y_floor = 0.0;
};

struct ProbeTable {
  sched::AccuracyGoal goal;
  std::vector<std::string> methods;    // candidates' method index -> name
  std::vector<std::string> schedules;  // candidates' schedule index -> name
  std::vector<sched::AccuracyCandidate> candidates;
  std::vector<ProbedState> states;
  // With a tolerance: whether some state resolves it (sched::resolves);
  // y is the worst over those states, or over all when none does.
  bool resolved = true;
  std::optional<std::size_t> scene_default;  // the scene's own method, iterations and schedule
  sched::AccuracyChoice choice;

  SolverChoice at(std::size_t candidate) const;
  double y_floor() const;  // the largest of the states'
};

class AccuracyProbe {
 public:
  // Measures the scene without friction (friction acts after the
  // iterations and is no part of the incremental potential). Throws
  // atssim::Error (input) for a method of solver.methods the scene
  // forbids, one that has no iterations to choose, or no method at all.
  // `ms_per_us` > 0: the cost model's scale for every device (ms per µs of
  // the reference device) instead of one profiled (tests: a budget decided
  // without timings).
  AccuracyProbe(const scene::SceneDesc& scene, const device::DeviceSet& devices, double ms_per_us = 0.0);
  ~AccuracyProbe();
  AccuracyProbe(const AccuracyProbe&) = delete;
  AccuracyProbe& operator=(const AccuracyProbe&) = delete;

  // The whole probe from `state` (x, v at the end of `frame`), measured on
  // `substeps` states, and the choice for the scene's goal.
  ProbeTable probe(const solver::SimLayout& state, int frame, int substeps);
  // A re-check: y of `choice` on `state` alone, and what the reference
  // measured there. With `resolution` > 0, NaN without running the choice
  // when the state does not resolve y to it (sched::resolves): y there is
  // float32 rounding. The state's reference is kept for a probe() of the
  // same state and frame that follows.
  double measure(const SolverChoice& choice, const solver::SimLayout& state, int frame, ProbedState* measured,
                 double resolution = 0.0);
  // The cost model's frame time for a choice, and its line in the iterations.
  double predicted_ms(const std::string& method, int iterations, const std::string& schedule);
  sched::IterationCost cost_line(const std::string& method, const std::string& schedule);
  bool has_cost_line(const std::string& method, const std::string& schedule) const;

  const std::vector<std::string>& methods() const;
  int max_iterations() const;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

// The probe's table as text: one row per method and iteration count, y and
// the predicted frame time per schedule; the choice and the scene's own
// settings marked.
std::string format_probe_table(const ProbeTable& table);

// The one line for a goal no choice meets: what was asked and what the
// nearest choices give.
std::string none_meets_message(const ProbeTable& table, int max_iterations);

}  // namespace atssim::app
