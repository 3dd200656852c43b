#include <catch2/catch.hpp>

#include "sched/lower_bound.hpp"

using namespace atssim::sched;

TEST_CASE("The critical-path bound sums minimum costs along the longest path", "[bound]") {
  // a → b, a → c; min costs a 2, b 1, c 4.
  TaskGraph g;
  for (const char* n : {"a", "b", "c"}) g.add_task({n, 0, -1, -1});
  g.add_edge(0, 1, 100);  // edge weights never count: both ends may share a device
  g.add_edge(0, 2, 100);
  const auto costs = CostTable::from_rows({{2, 3}, {5, 1}, {4, kCannotRun}});
  CHECK(critical_path_bound(g, costs) == 6.0);
  CHECK(work_bound(costs) == 3.5);
  CHECK(makespan_lower_bound(g, costs) == 6.0);
}

TEST_CASE("The work bound wins for many independent tasks", "[bound]") {
  TaskGraph g;
  for (int i = 0; i < 8; ++i) g.add_task({"t", 0, -1, -1});
  const CostTable costs(8, 2, 3.0);
  CHECK(critical_path_bound(g, costs) == 3.0);
  CHECK(makespan_lower_bound(g, costs) == 12.0);
}
