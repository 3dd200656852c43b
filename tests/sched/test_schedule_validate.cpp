// Schedule::validate must catch every way a schedule can be wrong.
#include <catch2/catch.hpp>

#include "sched/schedule.hpp"
#include "util/error.hpp"

using namespace atssim::sched;

namespace {

// a → b (weight 4) → c; a and b on device 0, c on device 1. Costs 2/3 ms.
struct Fixture {
  TaskGraph graph;
  CostTable costs = CostTable::from_rows({{2, 3}, {2, 3}, {kCannotRun, 3}});
  DeviceLinks links = DeviceLinks::weighted(2);
  Fixture() {
    graph.add_task({"a", 0, -1, -1});
    graph.add_task({"b", 0, -1, -1});
    graph.add_task({"c", 0, -1, -1});
    graph.add_edge(0, 1, 4.0);
    graph.add_edge(1, 2, 4.0);
  }
  // b finishes at 4; c on the other device needs +4 of communication.
  std::vector<std::vector<Slot>> good() const { return {{{0, 0, 2}, {1, 2, 4}}, {{2, 8, 11}}}; }
};

}  // namespace

TEST_CASE("A correct schedule validates", "[validate]") {
  const Fixture f;
  const Schedule s = assemble_schedule(3, f.good());
  CHECK(s.makespan_ms == 11.0);
  CHECK(s.validate(f.graph, f.costs, f.links).empty());
  CHECK_NOTHROW(s.throw_if_invalid(f.graph, f.costs, f.links));
}

TEST_CASE("validate reports each kind of broken schedule", "[validate]") {
  const Fixture f;
  using Slots = std::vector<std::vector<Slot>>;
  const auto [what, slots, expected] = GENERATE(table<std::string, Slots, std::string>({
      {"consumer before its input", {{{0, 0, 2}, {1, 2, 4}}, {{2, 4, 7}}}, "before its input"},
      {"overlap on one device", {{{0, 0, 2}, {1, 1, 3}}, {{2, 8, 11}}}, "before 'a' finishes"},
      {"wrong duration", {{{0, 0, 2}, {1, 2, 5}}, {{2, 9, 12}}}, "its cost is 2 ms"},
      {"device that cannot run it", {{{0, 0, 2}, {1, 2, 4}, {2, 4, 4}}, {}}, "cannot run it"},
      {"task missing", {{{0, 0, 2}, {1, 2, 4}}, {}}, "'c' is scheduled 0 times"},
      {"task twice", {{{0, 0, 2}, {1, 2, 4}}, {{2, 8, 11}, {2, 11, 14}}}, "'c' is scheduled 2"},
  }));
  CAPTURE(what);
  const Schedule s = assemble_schedule(3, slots);
  const auto problems = s.validate(f.graph, f.costs, f.links);
  REQUIRE_FALSE(problems.empty());
  std::string all;
  for (const auto& p : problems) all += p + "\n";
  CHECK_THAT(all, Catch::Contains(expected));
  CHECK_THROWS_AS(s.throw_if_invalid(f.graph, f.costs, f.links), atssim::Error);
}

TEST_CASE("validate reports a start before the device's ready time", "[validate]") {
  const Fixture f;
  const Schedule s = assemble_schedule(3, f.good(), {1.0, 0.0});
  CHECK_THAT(s.validate(f.graph, f.costs, f.links).at(0), Catch::Contains("busy until 1 ms"));
}

TEST_CASE("validate reports a makespan that is not the latest finish", "[validate]") {
  const Fixture f;
  Schedule s = assemble_schedule(3, f.good());
  s.makespan_ms = 10.0;
  CHECK_THAT(s.validate(f.graph, f.costs, f.links).at(0), Catch::Contains("latest finish"));
}
