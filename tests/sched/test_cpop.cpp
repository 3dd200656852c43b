// CPOP against the published Topcuoglu, Hariri & Wu (2002) example.
#include <catch2/catch.hpp>

#include "classic_graphs.hpp"
#include "sched/cpop.hpp"

using namespace atssim::sched;
using atssim::sched::test::topcuoglu_2002;

TEST_CASE("CPOP finds the Topcuoglu 2002 critical path n1-n2-n9-n10", "[cpop]") {
  const auto p = topcuoglu_2002();
  CHECK(cpop_critical_path(p.graph, p.costs, p.links) == std::vector<TaskId>{0, 1, 8, 9});
}

TEST_CASE("CPOP reproduces the Topcuoglu 2002 makespan of 86", "[cpop]") {
  const auto p = topcuoglu_2002();
  const Schedule s = schedule_cpop(p.graph, p.costs, p.links);
  CHECK(s.makespan_ms == 86.0);
  CHECK(s.validate(p.graph, p.costs, p.links).empty());
}

TEST_CASE("CPOP puts the whole critical path on the device that runs it fastest", "[cpop]") {
  // Path costs: P1 14+13+18+21 = 66, P2 16+19+12+7 = 54, P3 9+18+20+16 = 63.
  const auto p = topcuoglu_2002();
  const Schedule s = schedule_cpop(p.graph, p.costs, p.links);
  for (TaskId t : {0u, 1u, 8u, 9u}) {
    CAPTURE(p.graph.task(t).name);
    CHECK(s.device_of(t) == 1);
  }
}

TEST_CASE("CPOP leaves an extra device that can run nothing empty", "[cpop]") {
  const auto p = topcuoglu_2002();
  auto costs = p.costs;
  costs.add_device();
  const Schedule s = schedule_cpop(p.graph, costs, DeviceLinks::weighted(4));
  CHECK(s.devices[3].empty());
  CHECK(s.makespan_ms == 86.0);
}
