#pragma once
// Choosing how accurately to solve (`run --tolerance` / `--budget`): from
// what a probe measured — the relative energy error y of one substep per
// method and iteration count, against a Newton reference — and the frame
// time the cost model predicts for each choice, the cheapest choice that
// meets a tolerance, or the most accurate one that fits a budget. Pure:
// tables in, a choice out; the same table always gives the same choice.
#include <cstddef>
#include <limits>
#include <optional>
#include <span>
#include <vector>

namespace atssim::sched {

// One probed choice. `method` and `schedule` index the caller's lists
// (their order breaks ties, so list them in a fixed order).
struct AccuracyCandidate {
  int method = 0;
  int iterations = 0;
  int schedule = 0;
  double y = 0.0;             // relative energy error (the worst over the probe's states); NaN: not measured
  double predicted_ms = 0.0;  // per frame, from the cost model
};

struct AccuracyGoal {
  double tolerance = 0.0;  // wanted: y <= tolerance; 0 = no tolerance
  double budget_ms = 0.0;  // wanted: predicted_ms <= budget_ms; 0 = no budget
};

struct AccuracyChoice {
  std::optional<std::size_t> chosen;  // index into the candidates; empty when none meets the goal
  // When none does: the nearest ones, best first — with a tolerance the
  // most accurate (those within the budget first, when there is one), with
  // a budget alone the cheapest. At most one per method.
  std::vector<std::size_t> nearest;
};

// With a tolerance: the cheapest candidate whose y meets it (and whose
// predicted time fits the budget, when there is one as well). With a budget
// alone: the most accurate candidate that fits it. Ties go to the smaller
// y, then the smaller time, then fewer iterations, then the earlier method
// and schedule. A candidate whose y or time is NaN never meets a goal.
// Throws atssim::Error (an internal error: a caller's bug) for a goal with neither.
AccuracyChoice choose_accuracy(std::span<const AccuracyCandidate> candidates, const AccuracyGoal& goal);

// The iteration counts a probe tries, up to `max`: about √2 apart (1, 2, 3,
// 4, 6, 8, 11, 16, 23, 32, 45, 64, …), so that the count chosen is at most
// ~1.4× the least that meets a tolerance; `also` (the scene's own count) is
// added when it lies in range. Ascending, no repeats.
std::vector<int> iteration_ladder(int max, int also = 0);

// Frame time linear in the iterations: what a substep costs besides them
// (predict, the velocity update, contact detection) and per iteration,
// times the substeps. From the predicted frame times of 1 and 2 iterations.
struct IterationCost {
  double fixed_ms = 0.0;
  double per_iteration_ms = 0.0;

  static IterationCost from_two(double one_iteration_ms, double two_iterations_ms);
  double at(int iterations) const { return fixed_ms + per_iteration_ms * iterations; }
  // The most iterations whose time fits `budget_ms` (0 when not even one does).
  int most_within(double budget_ms) const;
};

// Budget feedback: the frame time measured so far runs `measured_ms`
// against the `predicted_ms` the choice was made for. The iterations that
// fit the budget when every predicted time is scaled by that ratio, at
// least 1. The measured time is the median of the frames since the last
// check, so one slow frame does not move it.
int iterations_for_budget(const IterationCost& predicted, double predicted_ms, double measured_ms, double budget_ms);

// Why a budget alone was not held: the run's median frame time
// `measured_ms`, with `iterations` in force at the end (of at most
// `max_iterations`), against budget·(1 ± band). `next_ms`: the frame time
// predicted for one iteration more, on the measured scale (NaN: not known).
enum class BudgetMiss {
  none,       // within the band (or nothing measured)
  too_small,  // above it with one iteration: what a frame costs besides the iterations exceeds the budget
  too_large,  // below it with the most iterations tried: no choice needs that much time
  granular,   // below it, and one iteration more is predicted over the budget: the budget lies between two counts
  unsettled,  // off it with iterations to spare: the frame time moved (load), or the run ended before a re-check
};
BudgetMiss budget_miss(double budget_ms, double measured_ms, int iterations, int max_iterations, double band = 0.1,
                       double next_ms = std::numeric_limits<double>::quiet_NaN());

// What a re-check on the live state does with the choice in force.
enum class Recheck {
  keep,     // it still meets the goal (or the state cannot tell)
  reprobe,  // its y went above the tolerance: probe again and choose again
  rescale,  // a budget alone, and the measured frame time left the budget's ±band: new iterations
};

// `y`: the choice's error measured on the state; `resolved`: whether the
// state resolves y to the tolerance (its float32 floor is well below it);
// `measured_ms`: the median frame time since the last re-check. With a
// tolerance, y decides (and the budget only filters the next choice); with
// a budget alone, time outside budget·(1 ± band) rescales.
Recheck recheck_verdict(const AccuracyGoal& goal, double y, bool resolved, double measured_ms, double band = 0.1);

// Whether a state whose float32 floor of y is `y_floor` can tell choices
// apart at `tolerance`: the floor must lie a factor `margin` below it
// (methods' own rounding ends ~2× above the floor).
bool resolves(double y_floor, double tolerance, double margin = 4.0);

// The y a state must resolve for `goal` to tell its choices apart: the
// tolerance, or with a budget alone 1e-2 (a budget ranks the choices by y,
// and only differences well above float32 rounding rank them).
double resolution_needed(const AccuracyGoal& goal);

}  // namespace atssim::sched
