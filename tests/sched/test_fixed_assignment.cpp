#include <catch2/catch.hpp>

#include "sched/fixed_assignment.hpp"
#include "sched/heft.hpp"
#include "util/error.hpp"

using namespace atssim;
using namespace atssim::sched;

namespace {

// a -> {b, c} -> d, costs per device.
TaskGraph diamond() {
  TaskGraph g;
  for (const char* n : {"a", "b", "c", "d"}) g.add_task({n, 0, -1, -1});
  g.add_edge(0, 1);
  g.add_edge(0, 2);
  g.add_edge(1, 3);
  g.add_edge(2, 3);
  return g;
}

}  // namespace

TEST_CASE("everything on one device runs back to back: makespan is the sum of its costs") {
  const TaskGraph g = diamond();
  const CostTable costs = CostTable::from_rows({{1, 2}, {3, 4}, {5, 6}, {7, 8}});
  const DeviceLinks links = DeviceLinks::unified_memory(2, 0.5);
  const Schedule s = schedule_fixed(g, costs, links, {1, 1, 1, 1});
  CHECK(s.makespan_ms == Approx(2 + 4 + 6 + 8));
  CHECK(s.devices[0].empty());
  CHECK(s.validate(g, costs, links).empty());
  CHECK(s.cross_device_waits(g).empty());
}

TEST_CASE("a fixed split pays the link latency at each cross-device edge") {
  const TaskGraph g = diamond();
  const CostTable costs = CostTable::from_rows({{1, 1}, {3, 3}, {5, 5}, {1, 1}});
  const DeviceLinks links = DeviceLinks::unified_memory(2, 0.5);
  const Schedule s = schedule_fixed(g, costs, links, {0, 0, 1, 0});
  // c starts after a's 1 ms + 0.5 ms hop, ends at 6.5; d waits for it (+0.5).
  CHECK(s.slot(2).start_ms == Approx(1.5));
  CHECK(s.slot(3).start_ms == Approx(7.0));
  CHECK(s.makespan_ms == Approx(8.0));
  CHECK(s.validate(g, costs, links).empty());
  CHECK(s.cross_device_waits(g).size() == 2);
}

TEST_CASE("re-timing HEFT's own assignment without insertion never beats HEFT's makespan by much") {
  // The classic diamond has no gaps to fill, so both must agree exactly.
  const TaskGraph g = diamond();
  const CostTable costs = CostTable::from_rows({{2, 3}, {4, 2}, {3, 5}, {1, 1}});
  const DeviceLinks links = DeviceLinks::unified_memory(2, 0.2);
  const Schedule heft = schedule_heft(g, costs, links);
  std::vector<DeviceId> assignment;
  for (TaskId t = 0; t < g.size(); ++t) assignment.push_back(heft.device_of(t));
  const Schedule fixed = schedule_fixed(g, costs, links, assignment);
  CHECK(fixed.makespan_ms == Approx(heft.makespan_ms));
  CHECK(fixed.validate(g, costs, links).empty());
}

TEST_CASE("assigning a task to a device that cannot run it is an error") {
  const TaskGraph g = diamond();
  CostTable costs = CostTable::from_rows({{1, 1}, {1, 1}, {1, 1}, {1, 1}});
  costs.at(2, 1) = kCannotRun;
  CHECK_THROWS_AS(schedule_fixed(g, costs, DeviceLinks::unified_memory(2, 0.1), {0, 0, 1, 0}), Error);
}
