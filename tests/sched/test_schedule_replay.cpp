#include <catch2/catch.hpp>

#include "sched/schedule.hpp"

using namespace atssim::sched;

TEST_CASE("a replay runs every task on device 0 in the order of its predicted start") {
  // Predicted: device 0 runs 0 then 2, device 1 runs 1 (starting with 0)
  // then 3. In start order: 0 and 1 (a tie keeps task order), 3, 2.
  const Schedule s = assemble_schedule(4, {{{0, 0.0, 1.0}, {2, 3.0, 4.0}}, {{1, 0.0, 2.0}, {3, 2.0, 3.0}}});
  const CostTable costs = CostTable::from_rows({{1.0, 9.0}, {2.0, 9.0}, {3.0, 9.0}, {4.0, 9.0}});
  const Schedule r = replay_on_device0(s, costs, 2);
  REQUIRE(r.devices.size() == 2);
  CHECK(r.devices[1].empty());
  REQUIRE(r.devices[0].size() == 4);
  const std::vector<Slot> expected{{0, 0.0, 1.0}, {1, 1.0, 3.0}, {3, 3.0, 7.0}, {2, 7.0, 10.0}};
  for (std::size_t i = 0; i < expected.size(); ++i) {
    CHECK(r.devices[0][i].task == expected[i].task);
    CHECK(r.devices[0][i].start_ms == expected[i].start_ms);
    CHECK(r.devices[0][i].finish_ms == expected[i].finish_ms);
  }
  CHECK(r.makespan_ms == 10.0);
}
