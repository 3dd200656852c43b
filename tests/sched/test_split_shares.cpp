#include <catch2/catch.hpp>

#include "sched/split_shares.hpp"

using namespace atssim::sched;

namespace {

// A whole task, then one task cut in two parts: the tasks split_plan makes
// from "predict" and "it1/stretch/c0".
TaskGraph whole_and_two_parts() {
  TaskGraph g;
  g.add_task({"predict", 1, -1, -1, -1});
  g.add_task({"it1/stretch/c0#0", 2, 0, 0, 0});
  g.add_task({"it1/stretch/c0#1", 2, 0, 0, 1});
  g.add_edge(0, 1);
  g.add_edge(0, 2);
  return g;
}

}  // namespace

TEST_CASE("split fractions follow each device's speed on the whole substep") {
  // Device 0 needs 1 + 2 = 3 ms, device 1 needs 4 + 2 = 6 ms: speeds 1/3 and
  // 1/6, so device 0 takes two thirds.
  const CostTable costs = CostTable::from_rows({{1.0, 4.0}, {2.0, 2.0}});
  const auto f = speed_fractions(costs);
  REQUIRE(f.size() == 2);
  CHECK(f[0] == Approx(2.0 / 3.0));
  CHECK(f[1] == Approx(1.0 / 3.0));
  CHECK(equal_fractions(4) == std::vector<double>{0.25, 0.25, 0.25, 0.25});
}

TEST_CASE("part k runs on device k and a whole task on device 0") {
  CHECK(part_devices(whole_and_two_parts()) == std::vector<DeviceId>{0, 0, 1});
}

TEST_CASE("costs of an equal cut carried to another cut scale each part by its share") {
  // Measured on halves: part 0 costs 2 ms on either device, part 1 4 ms.
  // Cut 3/4 : 1/4, part 0 does 1.5 times the elements, part 1 half of them;
  // the whole task keeps its cost.
  const CostTable equal = CostTable::from_rows({{1.0, 3.0}, {2.0, 2.0}, {4.0, 4.0}});
  const std::vector<double> fractions{0.75, 0.25};
  const CostTable cut = costs_for_fractions(whole_and_two_parts(), equal, fractions);
  CHECK(cut.at(0, 0) == 1.0);
  CHECK(cut.at(0, 1) == 3.0);
  CHECK(cut.at(1, 0) == 3.0);
  CHECK(cut.at(1, 1) == 3.0);
  CHECK(cut.at(2, 0) == 2.0);
  CHECK(cut.at(2, 1) == 2.0);
}

TEST_CASE("costs for a cut of another graph or device count are refused") {
  const CostTable two_tasks(2, 2, 1.0);
  const std::vector<double> halves{0.5, 0.5};
  CHECK_THROWS_WITH(costs_for_fractions(whole_and_two_parts(), two_tasks, halves),
                    Catch::Contains("a graph of 3 tasks cut in 2 parts, costs of 2 tasks"));
}

TEST_CASE("a re-cut scales each task's costs by its new share over its old one") {
  // Shares of a whole task (1), two parts moved from 1/2 : 1/2 to 3/4 : 1/4,
  // and a part that had no elements before (it keeps its costs).
  const std::vector<double> before{1.0, 0.5, 0.5, 0.0};
  const std::vector<double> after{1.0, 0.75, 0.25, 0.25};
  CHECK(share_factors(before, after) == std::vector<double>{1.0, 1.5, 0.5, 1.0});
}
