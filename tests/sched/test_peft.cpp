// PEFT against the published Arabnejad & Barbosa (2014) sample DAG.
#include <catch2/catch.hpp>

#include "classic_graphs.hpp"
#include "sched/peft.hpp"

using namespace atssim::sched;
using atssim::sched::test::arabnejad_2014;
using atssim::sched::test::topcuoglu_2002;

TEST_CASE("The optimistic cost table of the PEFT sample DAG matches the published one", "[peft]") {
  const auto p = arabnejad_2014();
  const CostTable oct = optimistic_cost_table(p.graph, p.costs, p.links);
  // clang-format off
  const auto [task, p1, p2, p3] = GENERATE(table<TaskId, double, double, double>({
      {0, 64, 68, 86}, {1, 42, 39, 42}, {2, 27, 41, 43}, {3, 42, 39, 50}, {4, 28, 37, 28},
      {5, 42, 39, 44}, {6, 13, 16, 22}, {7, 13, 16, 33}, {8, 13, 16, 20}, {9, 0, 0, 0}}));
  // clang-format on
  CAPTURE(p.graph.task(task).name);
  CHECK(oct.at(task, 0) == p1);
  CHECK(oct.at(task, 1) == p2);
  CHECK(oct.at(task, 2) == p3);
}

TEST_CASE("PEFT reproduces the published makespan of 122 on its sample DAG", "[peft]") {
  const auto p = arabnejad_2014();
  const Schedule s = schedule_peft(p.graph, p.costs, p.links);
  CHECK(s.makespan_ms == 122.0);
  CHECK(s.validate(p.graph, p.costs, p.links).empty());
}

TEST_CASE("PEFT places the sample DAG's tasks on the published processors and times", "[peft]") {
  const auto p = arabnejad_2014();
  const Schedule s = schedule_peft(p.graph, p.costs, p.links);
  // clang-format off
  const auto [task, device, start, finish] = GENERATE(table<TaskId, DeviceId, double, double>({
      {0, 0, 0, 22}, {3, 0, 22, 29}, {1, 0, 29, 51}, {2, 0, 51, 83}, {6, 0, 83, 97},
      {5, 1, 29, 46}, {7, 1, 54, 77}, {9, 1, 106, 122}, {4, 2, 35, 70}, {8, 2, 81, 89}}));
  // clang-format on
  CAPTURE(p.graph.task(task).name);
  CHECK(s.device_of(task) == device);
  CHECK(s.slot(task).start_ms == start);
  CHECK(s.slot(task).finish_ms == finish);
}

TEST_CASE("PEFT schedules the Topcuoglu 2002 graph validly and leaves an unusable device empty", "[peft]") {
  const auto p = topcuoglu_2002();
  auto costs = p.costs;
  costs.add_device();
  const auto links = DeviceLinks::weighted(4);
  const Schedule s = schedule_peft(p.graph, costs, links);
  CHECK(s.validate(p.graph, costs, links).empty());
  CHECK(s.devices[3].empty());
  CHECK(s.makespan_ms == schedule_peft(p.graph, p.costs, p.links).makespan_ms);
}
