#include <catch2/catch.hpp>

#include <cmath>
#include <limits>
#include <vector>

#include "sched/accuracy_choice.hpp"
#include "util/error.hpp"

using namespace atssim;
using sched::AccuracyCandidate;

namespace {

constexpr double not_measured = std::numeric_limits<double>::quiet_NaN();

// Two methods, the y of docs/accuracy.md's 64x64 hanging cloth (VBD and
// JPGD, single schedule) with frame times linear in the iterations.
std::vector<AccuracyCandidate> cloth_table() {
  std::vector<AccuracyCandidate> t;
  const int ks[] = {1, 8, 16, 32, 64, 128};
  const double vbd[] = {0.264, 0.086, 0.060, 0.040, 0.025, 0.013};
  const double jpgd[] = {0.296, 0.107, 0.077, 0.055, 0.036, 0.021};
  for (int i = 0; i < 6; ++i) {
    t.push_back({0, ks[i], 0, vbd[i], 2.0 + 2.8 * ks[i]});
    t.push_back({1, ks[i], 0, jpgd[i], 2.0 + 2.5 * ks[i]});
  }
  return t;
}

}  // namespace

TEST_CASE("a tolerance picks the cheapest candidate whose error meets it") {
  const auto t = cloth_table();
  // y <= 0.05: VBD needs 32 iterations (91.6 ms), JPGD 64 (162 ms).
  auto c = sched::choose_accuracy(t, {0.05, 0.0});
  REQUIRE(c.chosen);
  CHECK(t[*c.chosen].method == 0);
  CHECK(t[*c.chosen].iterations == 32);
  // y <= 0.1: VBD at 8 (24.4 ms) and JPGD at 16 (42 ms) meet it: VBD.
  c = sched::choose_accuracy(t, {0.1, 0.0});
  REQUIRE(c.chosen);
  CHECK(t[*c.chosen].iterations == 8);
  CHECK(t[*c.chosen].method == 0);
  // y <= 0.3: everything at one iteration; JPGD's is cheaper (4.5 < 4.8 ms).
  c = sched::choose_accuracy(t, {0.3, 0.0});
  REQUIRE(c.chosen);
  CHECK(t[*c.chosen].method == 1);
  CHECK(t[*c.chosen].iterations == 1);
}

TEST_CASE("a tighter tolerance never chooses a cheaper candidate") {
  const auto t = cloth_table();
  double last_ms = 0.0;
  for (double tol : {0.3, 0.1, 0.05, 0.03, 0.02, 0.015}) {
    const auto c = sched::choose_accuracy(t, {tol, 0.0});
    REQUIRE(c.chosen);
    INFO("tolerance " << tol);
    CHECK(t[*c.chosen].y <= tol);
    CHECK(t[*c.chosen].predicted_ms >= last_ms);
    last_ms = t[*c.chosen].predicted_ms;
  }
}

TEST_CASE("a tolerance none meets names the most accurate candidates, one per method") {
  const auto t = cloth_table();
  const auto c = sched::choose_accuracy(t, {1e-4, 0.0});
  CHECK_FALSE(c.chosen);
  REQUIRE(c.nearest.size() == 2);
  CHECK(t[c.nearest[0]].method == 0);
  CHECK(t[c.nearest[0]].y == 0.013);
  CHECK(t[c.nearest[1]].method == 1);
  CHECK(t[c.nearest[1]].y == 0.021);
}

TEST_CASE("a budget picks the most accurate candidate whose predicted time fits it") {
  const auto t = cloth_table();
  // 100 ms: VBD 32 (91.6 ms, y 0.040) against JPGD 32 (82 ms, y 0.055).
  auto c = sched::choose_accuracy(t, {0.0, 100.0});
  REQUIRE(c.chosen);
  CHECK(t[*c.chosen].method == 0);
  CHECK(t[*c.chosen].iterations == 32);
  // 3 ms: nothing fits (the cheapest, JPGD at 1, needs 4.5 ms).
  c = sched::choose_accuracy(t, {0.0, 3.0});
  CHECK_FALSE(c.chosen);
  REQUIRE(c.nearest.size() == 2);
  CHECK(t[c.nearest[0]].predicted_ms == Approx(4.5));
  CHECK(t[c.nearest[1]].predicted_ms == Approx(4.8));
}

TEST_CASE("a tolerance with a budget wants both, and names the nearest within the budget first") {
  const auto t = cloth_table();
  auto c = sched::choose_accuracy(t, {0.05, 100.0});
  REQUIRE(c.chosen);
  CHECK(t[*c.chosen].iterations == 32);
  // y <= 0.03 needs VBD at 64 (181 ms): over a 100 ms budget.
  c = sched::choose_accuracy(t, {0.03, 100.0});
  CHECK_FALSE(c.chosen);
  REQUIRE_FALSE(c.nearest.empty());
  CHECK(t[c.nearest[0]].predicted_ms <= 100.0);
  CHECK(t[c.nearest[0]].y == 0.040);
}

TEST_CASE("the choice does not depend on the order of the table, and ties go by a fixed order") {
  auto t = cloth_table();
  // Two schedules of equal time and error: the earlier schedule wins.
  t.push_back({0, 32, 1, 0.040, 2.0 + 2.8 * 32});
  const auto a = sched::choose_accuracy(t, {0.05, 0.0});
  std::vector<AccuracyCandidate> reversed(t.rbegin(), t.rend());
  const auto b = sched::choose_accuracy(reversed, {0.05, 0.0});
  REQUIRE(a.chosen);
  REQUIRE(b.chosen);
  CHECK(t[*a.chosen].schedule == 0);
  CHECK(reversed[*b.chosen].schedule == 0);
  CHECK(reversed[*b.chosen].method == t[*a.chosen].method);
  CHECK(reversed[*b.chosen].iterations == t[*a.chosen].iterations);
}

TEST_CASE("a candidate whose error or time was not measured never meets a goal") {
  std::vector<AccuracyCandidate> t{{0, 1, 0, not_measured, 1.0}, {1, 1, 0, 0.5, not_measured}, {2, 4, 0, 0.2, 9.0}};
  auto c = sched::choose_accuracy(t, {0.9, 0.0});
  REQUIRE(c.chosen);
  CHECK(*c.chosen == 2);
  c = sched::choose_accuracy(t, {0.0, 5.0});
  CHECK_FALSE(c.chosen);
  CHECK_THROWS_AS(sched::choose_accuracy(t, {0.0, 0.0}), Error);
}

TEST_CASE("the iteration ladder steps by about the square root of two and takes the scene's count") {
  CHECK(sched::iteration_ladder(64) == std::vector<int>{1, 2, 3, 4, 6, 8, 11, 16, 23, 32, 45, 64});
  CHECK(sched::iteration_ladder(10, 5) == std::vector<int>{1, 2, 3, 4, 5, 6, 8});
  CHECK(sched::iteration_ladder(10, 8) == std::vector<int>{1, 2, 3, 4, 6, 8});
  CHECK(sched::iteration_ladder(1) == std::vector<int>{1});
  for (int max : {100, 1000, 4096}) {
    const auto ks = sched::iteration_ladder(max);
    for (std::size_t i = 2; i < ks.size(); ++i) CHECK(double(ks[i]) / ks[i - 1] <= 1.5 + 1e-9);  // from 2 on
  }
}

TEST_CASE("frame time linear in the iterations: from two points, and the most that fit a budget") {
  const auto c = sched::IterationCost::from_two(5.0, 8.0);  // 2 + 3 k
  CHECK(c.fixed_ms == Approx(2.0));
  CHECK(c.per_iteration_ms == Approx(3.0));
  CHECK(c.at(10) == Approx(32.0));
  CHECK(c.most_within(32.0) == 10);
  CHECK(c.most_within(31.9) == 9);
  CHECK(c.most_within(4.9) == 0);
  // Measured frames run 2x the prediction: half the budget's worth.
  CHECK(sched::iterations_for_budget(c, 32.0, 64.0, 64.0) == 10);
  CHECK(sched::iterations_for_budget(c, 32.0, 16.0, 32.0) == 20);
  CHECK(sched::iterations_for_budget(c, 32.0, 640.0, 32.0) == 1);  // at least one
}

TEST_CASE("a re-check probes again only when the error went above the tolerance on a state that resolves it") {
  using sched::Recheck;
  const sched::AccuracyGoal tol{1e-2, 0.0};
  CHECK(sched::recheck_verdict(tol, 5e-3, true, 10.0) == Recheck::keep);
  CHECK(sched::recheck_verdict(tol, 1e-2, true, 10.0) == Recheck::keep);
  CHECK(sched::recheck_verdict(tol, 2e-2, true, 10.0) == Recheck::reprobe);
  CHECK(sched::recheck_verdict(tol, 2e-2, false, 10.0) == Recheck::keep);  // float32 cannot tell
  CHECK(sched::recheck_verdict(tol, not_measured, true, 10.0) == Recheck::keep);
  // With a budget as well, time does not rescale: the tolerance decides.
  CHECK(sched::recheck_verdict({1e-2, 5.0}, 5e-3, true, 50.0) == Recheck::keep);
}

TEST_CASE("a budget alone rescales when the measured frame time leaves the 10 % band") {
  using sched::Recheck;
  const sched::AccuracyGoal budget{0.0, 20.0};
  CHECK(sched::recheck_verdict(budget, 0.5, true, 21.9) == Recheck::keep);
  CHECK(sched::recheck_verdict(budget, 0.5, true, 18.1) == Recheck::keep);
  CHECK(sched::recheck_verdict(budget, 0.5, true, 22.1) == Recheck::rescale);
  CHECK(sched::recheck_verdict(budget, 0.5, true, 17.9) == Recheck::rescale);
  CHECK(sched::recheck_verdict(budget, 0.5, true, not_measured) == Recheck::keep);
}

TEST_CASE(
    "a budget missed by more than 10 % names why: one iteration, the most iterations, a budget between two counts, or "
    "a moving frame time") {
  using sched::BudgetMiss;
  CHECK(sched::budget_miss(20.0, 21.9, 1, 1024) == BudgetMiss::none);
  CHECK(sched::budget_miss(20.0, 18.1, 1024, 1024) == BudgetMiss::none);
  CHECK(sched::budget_miss(20.0, not_measured, 1, 1024) == BudgetMiss::none);
  CHECK(sched::budget_miss(20.0, 22.1, 1, 1024) == BudgetMiss::too_small);
  CHECK(sched::budget_miss(20.0, 22.1, 2, 1024) == BudgetMiss::unsettled);
  CHECK(sched::budget_miss(20.0, 17.9, 1024, 1024) == BudgetMiss::too_large);
  CHECK(sched::budget_miss(20.0, 17.9, 1, 1024) == BudgetMiss::unsettled);
  CHECK(sched::budget_miss(20.0, 25.0, 1, 1024, 0.3) == BudgetMiss::none);
  // docs/accuracy.md, --budget 30: VBD 2 measured 20.5 ms, VBD 3 predicted
  // ~31 ms on the measured scale: the budget lies between two counts.
  CHECK(sched::budget_miss(30.0, 20.5, 2, 1024, 0.1, 31.0) == BudgetMiss::granular);
  CHECK(sched::budget_miss(30.0, 20.5, 2, 1024, 0.1, 29.0) == BudgetMiss::unsettled);  // 3 would fit: not granular
  CHECK(sched::budget_miss(30.0, 20.5, 1024, 1024, 0.1, 31.0) == BudgetMiss::too_large);
  CHECK(sched::budget_miss(30.0, 34.0, 2, 1024, 0.1, 45.0) == BudgetMiss::unsettled);  // above: fewer would fit
  CHECK(sched::budget_miss(30.0, 28.0, 2, 1024, 0.1, 40.0) == BudgetMiss::none);
}

TEST_CASE("a state resolves a tolerance when its float32 floor lies four times below it") {
  CHECK(sched::resolves(2e-3, 1e-2));
  CHECK(sched::resolves(2.5e-3, 1e-2));
  CHECK_FALSE(sched::resolves(3e-3, 1e-2));
  CHECK_FALSE(sched::resolves(not_measured, 1e-2));  // E0 = E*: nothing to solve
  CHECK(sched::resolution_needed({1e-4, 0.0}) == 1e-4);
  CHECK(sched::resolution_needed({1e-4, 20.0}) == 1e-4);
  CHECK(sched::resolution_needed({0.0, 20.0}) == 1e-2);
}
