#include "sched/accuracy_choice.hpp"

#include <algorithm>
#include <cmath>
#include <numeric>
#include <tuple>

#include "util/error.hpp"

namespace atssim::sched {

namespace {

bool measured(const AccuracyCandidate& c) { return std::isfinite(c.y) && std::isfinite(c.predicted_ms); }

// The order of preference among candidates that all meet the goal: the
// primary figure (time, or y under a budget), then the other, then fewer
// iterations, then the lists' order. A strict total order on distinct
// candidates, so the choice never depends on the order of the table.
bool better(const AccuracyCandidate& a, const AccuracyCandidate& b, bool by_time) {
  const double a1 = by_time ? a.predicted_ms : a.y, b1 = by_time ? b.predicted_ms : b.y;
  const double a2 = by_time ? a.y : a.predicted_ms, b2 = by_time ? b.y : b.predicted_ms;
  return std::tie(a1, a2, a.iterations, a.method, a.schedule) < std::tie(b1, b2, b.iterations, b.method, b.schedule);
}

// Indices of `candidates` that pass `keep`, best first by `by_time`.
template <typename Keep>
std::vector<std::size_t> ranked(std::span<const AccuracyCandidate> candidates, bool by_time, Keep keep) {
  std::vector<std::size_t> out;
  for (std::size_t i = 0; i < candidates.size(); ++i) {
    if (measured(candidates[i]) && keep(candidates[i])) out.push_back(i);
  }
  std::sort(out.begin(), out.end(),
            [&](std::size_t a, std::size_t b) { return better(candidates[a], candidates[b], by_time); });
  return out;
}

// The first of `order` for each method, at most `count` of them.
std::vector<std::size_t> one_per_method(std::span<const AccuracyCandidate> candidates,
                                        const std::vector<std::size_t>& order, std::size_t count) {
  std::vector<std::size_t> out;
  std::vector<int> methods;
  for (std::size_t i : order) {
    if (out.size() == count) break;
    if (std::find(methods.begin(), methods.end(), candidates[i].method) != methods.end()) continue;
    methods.push_back(candidates[i].method);
    out.push_back(i);
  }
  return out;
}

}  // namespace

AccuracyChoice choose_accuracy(std::span<const AccuracyCandidate> candidates, const AccuracyGoal& goal) {
  const bool tolerance = goal.tolerance > 0.0, budget = goal.budget_ms > 0.0;
  if (!tolerance && !budget)
    throw runtime_error("internal error: choose_accuracy: a goal needs a tolerance or a budget");
  const auto meets = [&](const AccuracyCandidate& c) { return !tolerance || c.y <= goal.tolerance; };
  const auto fits = [&](const AccuracyCandidate& c) { return !budget || c.predicted_ms <= goal.budget_ms; };
  AccuracyChoice choice;
  const std::vector<std::size_t> feasible =
      ranked(candidates, tolerance, [&](const AccuracyCandidate& c) { return meets(c) && fits(c); });
  if (!feasible.empty()) {
    choice.chosen = feasible.front();
    return choice;
  }
  if (tolerance) {
    // The most accurate, those within the budget first.
    std::vector<std::size_t> order = ranked(candidates, false, fits);
    if (budget) {
      const std::vector<std::size_t> over = ranked(candidates, false, [&](const auto& c) { return !fits(c); });
      order.insert(order.end(), over.begin(), over.end());
    }
    choice.nearest = one_per_method(candidates, order, 3);
  } else {
    choice.nearest = one_per_method(candidates, ranked(candidates, true, [](const auto&) { return true; }), 3);
  }
  return choice;
}

std::vector<int> iteration_ladder(int max, int also) {
  std::vector<int> ks;
  for (int i = 0;; ++i) {
    const int k = static_cast<int>(std::lround(std::pow(2.0, i / 2.0)));
    if (k > max) break;
    if (ks.empty() || ks.back() != k) ks.push_back(k);
  }
  if (also >= 1 && also <= max && std::find(ks.begin(), ks.end(), also) == ks.end()) {
    ks.insert(std::upper_bound(ks.begin(), ks.end(), also), also);
  }
  return ks;
}

IterationCost IterationCost::from_two(double one_iteration_ms, double two_iterations_ms) {
  IterationCost c;
  c.per_iteration_ms = std::max(0.0, two_iterations_ms - one_iteration_ms);
  c.fixed_ms = std::max(0.0, one_iteration_ms - c.per_iteration_ms);
  return c;
}

int IterationCost::most_within(double budget_ms) const {
  if (!(budget_ms >= at(1))) return 0;
  if (per_iteration_ms <= 0.0) return 1 << 20;
  return static_cast<int>(std::min(std::floor((budget_ms - fixed_ms) / per_iteration_ms), double(1 << 20)));
}

int iterations_for_budget(const IterationCost& predicted, double predicted_ms, double measured_ms, double budget_ms) {
  if (!(predicted_ms > 0.0) || !(measured_ms > 0.0)) return std::max(1, predicted.most_within(budget_ms));
  const double scale = measured_ms / predicted_ms;
  return std::max(1, predicted.most_within(budget_ms / scale));
}

BudgetMiss budget_miss(double budget_ms, double measured_ms, int iterations, int max_iterations, double band,
                       double next_ms) {
  if (!(budget_ms > 0.0) || !std::isfinite(measured_ms) || !(measured_ms > 0.0)) return BudgetMiss::none;
  if (std::abs(measured_ms - budget_ms) <= band * budget_ms) return BudgetMiss::none;
  if (measured_ms > budget_ms && iterations <= 1) return BudgetMiss::too_small;
  if (measured_ms < budget_ms && iterations >= max_iterations) return BudgetMiss::too_large;
  if (measured_ms < budget_ms && next_ms > budget_ms) return BudgetMiss::granular;
  return BudgetMiss::unsettled;
}

Recheck recheck_verdict(const AccuracyGoal& goal, double y, bool resolved, double measured_ms, double band) {
  if (goal.tolerance > 0.0) {
    if (!resolved || !std::isfinite(y)) return Recheck::keep;
    return y > goal.tolerance ? Recheck::reprobe : Recheck::keep;
  }
  if (goal.budget_ms > 0.0 && std::isfinite(measured_ms) && measured_ms > 0.0 &&
      std::abs(measured_ms - goal.budget_ms) > band * goal.budget_ms) {
    return Recheck::rescale;
  }
  return Recheck::keep;
}

bool resolves(double y_floor, double tolerance, double margin) {
  return std::isfinite(y_floor) && y_floor * margin <= tolerance;
}

double resolution_needed(const AccuracyGoal& goal) { return goal.tolerance > 0.0 ? goal.tolerance : 1e-2; }

}  // namespace atssim::sched
