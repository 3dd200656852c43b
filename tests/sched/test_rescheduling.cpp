// Refitting costs from measurements and re-scheduling onto busy devices.
#include <catch2/catch.hpp>

#include "classic_graphs.hpp"
#include "sched/cost_refit.hpp"
#include "sched/heft.hpp"
#include "util/error.hpp"

using namespace atssim::sched;
using atssim::sched::test::topcuoglu_2002;

TEST_CASE("Each measurement moves the cost halfway toward it by default", "[refit]") {
  CostTable costs = CostTable::from_rows({{10, 4}});
  const std::vector<Measurement> m{{0, 0, 20}, {0, 0, 20}, {0, 1, 2}};
  refit_costs(costs, m);
  CHECK(costs.at(0, 0) == 17.5);  // 10 → 15 → 17.5
  CHECK(costs.at(0, 1) == 3.0);
}

TEST_CASE("A smoothing weight of 1 trusts the last measurement alone", "[refit]") {
  CostTable costs = CostTable::from_rows({{10, 4}});
  const std::vector<Measurement> m{{0, 0, 20}, {0, 0, 7}};
  refit_costs(costs, m, {.weight = 1.0});
  CHECK(costs.at(0, 0) == 7.0);
}

TEST_CASE("A measurement on a device that cannot run the task is an error", "[refit]") {
  CostTable costs = CostTable::from_rows({{10, kCannotRun}});
  const std::vector<Measurement> m{{0, 1, 3}};
  CHECK_THROWS_WITH(refit_costs(costs, m), Catch::Contains("cannot run it"));
}

TEST_CASE("A negative or non-finite measurement is an error", "[refit]") {
  CostTable costs = CostTable::from_rows({{10, 4}});
  const double bad = GENERATE(-1.0, std::numeric_limits<double>::quiet_NaN(), kCannotRun);
  const std::vector<Measurement> m{{0, 0, bad}};
  CHECK_THROWS_AS(refit_costs(costs, m), atssim::Error);
}

TEST_CASE("Cost drift is the largest relative change of any entry", "[refit]") {
  const CostTable planned = CostTable::from_rows({{10, 4}, {2, kCannotRun}});
  CostTable now = planned;
  CHECK(cost_drift(planned, now) == 0.0);
  now.at(0, 1) = 5;    // +25 %
  now.at(1, 0) = 2.2;  // +10 %
  CHECK(cost_drift(planned, now) == Approx(0.25));
  now.at(1, 1) = 1;  // an inf entry became finite: the problem changed
  CHECK(cost_drift(planned, now) == kCannotRun);
}

TEST_CASE("The trimmed mean drops the warm-up outlier of pre-profiling", "[refit]") {
  CHECK(trimmed_mean({100, 1, 2, 3, 4, 5, 6, 7, 8, 9}, 0.1) == Approx(5.5));
  CHECK(trimmed_mean({3, 5}, 0.1) == 4.0);
}

TEST_CASE("Devices busy until t0 shift the whole Topcuoglu schedule by t0", "[rescheduling]") {
  const auto p = topcuoglu_2002();
  const Schedule base = schedule_heft(p.graph, p.costs, p.links);
  HeftOptions options;
  options.device_ready_ms = {25, 25, 25};
  const Schedule later = schedule_heft(p.graph, p.costs, p.links, options);
  CHECK(later.validate(p.graph, p.costs, p.links).empty());
  CHECK(later.makespan_ms == 105.0);
  for (TaskId t = 0; t < p.graph.size(); ++t) {
    CHECK(later.device_of(t) == base.device_of(t));
    CHECK(later.slot(t).start_ms == base.slot(t).start_ms + 25.0);
  }
}

TEST_CASE("A device busy until t0 gets no slot before t0", "[rescheduling]") {
  const auto p = topcuoglu_2002();
  HeftOptions options;
  options.device_ready_ms = {0, 0, 40};  // P3, HEFT's favourite at the start, is busy
  const Schedule s = schedule_heft(p.graph, p.costs, p.links, options);
  CHECK(s.validate(p.graph, p.costs, p.links).empty());
  for (const Slot& slot : s.devices[2]) CHECK(slot.start_ms >= 40.0);
  CHECK(s.device_of(0) != 2);
}

TEST_CASE("Re-scheduling with refitted costs moves work off a device measured slow", "[rescheduling]") {
  const auto p = topcuoglu_2002();
  const Schedule before = schedule_heft(p.graph, p.costs, p.links);
  // Every task ran three times slower than predicted on P3.
  std::vector<Measurement> measured;
  for (const Slot& slot : before.devices[2]) {
    measured.push_back({slot.task, 2, 3.0 * p.costs.at(slot.task, 2)});
  }
  CostTable refitted = p.costs;
  refit_costs(refitted, measured, {.weight = 1.0});
  CHECK(cost_drift(p.costs, refitted) == Approx(2.0));
  const Schedule after = schedule_heft(p.graph, refitted, p.links);
  CHECK(after.validate(p.graph, refitted, p.links).empty());
  CHECK(after.devices[2].size() < before.devices[2].size());
}
