#include <catch2/catch.hpp>

#include "sched/cost_model.hpp"

using namespace atssim::sched;

TEST_CASE("balanced fractions give the slower device a smaller share, in proportion to its speed") {
  // Tasks 0, 2 on device 0 and 1, 3 on device 1; each device has half the
  // work, and device 1 needs twice as long for it.
  const CostTable costs = CostTable::from_rows({{1.0, 9.0}, {9.0, 2.0}, {1.0, 9.0}, {9.0, 2.0}});
  const std::vector<DeviceId> assignment{0, 1, 0, 1};
  const std::vector<double> halves{0.5, 0.5};
  const auto f = balanced_fractions(costs, assignment, halves);
  REQUIRE(f.size() == 2);
  CHECK(f[0] == Approx(2.0 / 3.0));
  CHECK(f[1] == Approx(1.0 / 3.0));
}

TEST_CASE("balanced fractions stay put while the devices are within the tolerance") {
  const CostTable costs = CostTable::from_rows({{1.0, 9.0}, {9.0, 1.02}});
  const std::vector<DeviceId> assignment{0, 1};
  const std::vector<double> f{0.4, 0.6};
  CHECK(balanced_fractions(costs, assignment, f, 0.03) == f);
}

TEST_CASE("a task's cost is its device's time from the end of the task before it there") {
  const std::vector<TaskTiming> timings{
      {0, 0, 0.0, 1.0}, {1, 1, 0.5, 2.0}, {2, 0, 3.0, 4.0}, {3, 0, 4.25, 5.0}, {4, 0, 5.5, 6.0}};
  // Task 2 waited for task 1 on device 1; the others only for their queue.
  const std::vector<Wait> waits{{1, 1, 2, 0}};
  const auto m = task_costs(timings, 2, waits);
  REQUIRE(m.size() == 5);
  CHECK(m[0].ms == Approx(1.0));  // the first on its device: from its start
  CHECK(m[1].ms == Approx(1.5));
  CHECK(m[2].ms == Approx(1.0));  // the wait for another device is not its cost
  CHECK(m[3].ms == Approx(1.0));  // the launch gap after task 2 is
  CHECK(m[4].ms == Approx(1.0));
}

TEST_CASE("without task timings each device's costs scale to its measured launch") {
  CostTable costs = CostTable::from_rows({{1.0, 1.0}, {1.0, 1.0}, {2.0, 2.0}});
  const Schedule s = assemble_schedule(3, {{{0, 0.0, 1.0}, {1, 1.0, 2.0}}, {{2, 0.0, 2.0}}});
  const std::vector<LaunchTiming> launches{{0, 4, 16.0}, {1, 4, 8.0}};  // 4 vs 2 ms per substep
  refit_from_launches(costs, s, launches, 1.0);
  CHECK(costs.at(0, 0) == Approx(2.0));
  CHECK(costs.at(1, 0) == Approx(2.0));
  CHECK(costs.at(2, 1) == Approx(2.0));  // already right
}

TEST_CASE("the copies of a substep move a link's cost per byte halfway to what they measured") {
  // Link 0 → 1: 0.01 ms latency, 1e-6 ms per byte. Two copies of 1000 bytes
  // took 0.014 and 0.016 ms: (0.030 - 2 · 0.01) / 2000 = 5e-6 ms per byte,
  // so the link moves to 1e-6 + (5e-6 - 1e-6) / 2 = 3e-6. Link 1 → 0 saw no
  // copy and keeps its cost; a link priced by latency only (0 per byte) too.
  DeviceLinks links = DeviceLinks::weighted(3, 0.01, 1.0e-6);
  links.set_link(0, 2, 0.01, 0.0);
  CostModel model(CostTable(1, 3, 1.0), links);
  const std::vector<CopyTiming> copies{{0, 1, 1000, 0.014}, {0, 1, 1000, 0.016}, {0, 2, 1000, 5.0}};
  model.observe_copies(copies);
  CHECK(model.links().ms_per_weight[0 * 3 + 1] == Approx(3.0e-6));
  CHECK(model.links().ms_per_weight[1 * 3 + 0] == Approx(1.0e-6));
  CHECK(model.links().ms_per_weight[0 * 3 + 2] == 0.0);
  CHECK(model.links().latency_ms[0 * 3 + 1] == Approx(0.01));
}

TEST_CASE("a link that costs more per byte than planned asks for a new schedule") {
  // Planned at 1e-6 ms per byte; the copies measured 5e-6, the link moves to
  // 3e-6: 200 % above what the schedule was made with, over the 15 % threshold.
  CostModel model(CostTable(1, 2, 1.0), DeviceLinks::weighted(2, 0.01, 1.0e-6));
  CHECK_FALSE(model.drifted());
  const std::vector<CopyTiming> copies{{0, 1, 1000, 0.014}, {0, 1, 1000, 0.016}};
  model.observe_copies(copies);
  CHECK(link_drift(DeviceLinks::weighted(2, 0.01, 1.0e-6), model.links()) == Approx(2.0));
  CHECK(model.drifted());
  model.plan_made();  // the new schedule is made with the refitted link
  CHECK_FALSE(model.drifted());
  // Copies that measure what was planned change nothing.
  const std::vector<CopyTiming> same{{0, 1, 1000, 0.01 + 3.0e-3}};
  model.observe_copies(same);
  CHECK_FALSE(model.drifted());
}
