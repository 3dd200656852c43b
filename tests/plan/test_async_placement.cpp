#include <catch2/catch.hpp>

#include "plan/async_placement.hpp"

using namespace atssim;

namespace {

// A Gauss-Seidel kind, declared here as a method declares its own.
constexpr plan::TaskKind kBlock{{"test_block", true, false, false}};

// predict -> two Gauss-Seidel blocks -> update velocity, a chain (the relaxed
// graph of one iteration).
plan::SubstepPlan chain() {
  plan::SubstepPlan p;
  p.program = "test";
  p.add_task(plan::make_task("predict", plan::TaskKind::predict), {});
  p.add_task(plan::make_task("it1/block/c0", kBlock, 0, 0), {});
  p.add_task(plan::make_task("it1/block/c1", kBlock, 0, 1), {});
  p.add_task(plan::make_task("update_velocity", plan::TaskKind::update_velocity), {});
  for (sched::TaskId t = 1; t < 4; ++t) p.graph.add_edge(t - 1, t);
  return p;
}

}  // namespace

TEST_CASE("async placement keeps small blocks on the main device: a hop costs two predict sweeps there") {
  // Device 1 needs 1.5 + 3 + 3 + 1.5 = 9 ms for the substep, device 0 22 ms:
  // device 1 is the main device and runs predict and the velocity update
  // alone. A block on device 0 would end at 1.5 + 3 (the hop: 2 · 1.5) + 1 =
  // 5.5 ms, on device 1 at 1.5 + 3 = 4.5 ms, so both blocks stay.
  const sched::CostTable costs = sched::CostTable::from_rows({{10.0, 1.5}, {1.0, 3.0}, {1.0, 3.0}, {10.0, 1.5}});
  const plan::AsyncPlacement a = plan::place_async(chain(), costs, sched::DeviceLinks::unified_memory(2, 0.0), true);
  CHECK(a.main_device == 1);
  for (sched::TaskId t = 0; t < 4; ++t) CHECK(a.placed.device_of(t) == 1);
  CHECK(a.map.merges.empty());
  CHECK(a.placed.makespan_ms == Approx(9.0));
}

TEST_CASE("async placement moves blocks worth a hop to the other device, and the main device merges their result") {
  // Device 1 needs 1.5 + 10 + 10 + 1.5 = 23 ms, device 0 20 + 1 + 1 + 20 =
  // 42 ms: device 1 is the main device. Block c0 ends at 1.5 + 3 + 1 = 5.5 ms on device 0
  // against 11.5 on device 1; c1 follows it there (6.5 ms); the velocity
  // update, pinned to device 1, waits for the hop: 6.5 + 3 + 1.5 = 11 ms.
  const sched::CostTable costs = sched::CostTable::from_rows({{20.0, 1.5}, {1.0, 10.0}, {1.0, 10.0}, {20.0, 1.5}});
  const plan::AsyncPlacement a = plan::place_async(chain(), costs, sched::DeviceLinks::unified_memory(2, 0.0), true);
  CHECK(a.main_device == 1);
  CHECK(a.placed.device_of(0) == 1);
  CHECK(a.placed.device_of(1) == 0);
  CHECK(a.placed.device_of(2) == 0);
  CHECK(a.placed.device_of(3) == 1);
  CHECK(a.placed.makespan_ms == Approx(11.0));
  bool merged = false;
  for (const sched::Merge& m : a.map.merges) merged = merged || (m.consumer == 3 && m.producer == 2);
  CHECK(merged);
}

TEST_CASE("async placement refuses costs that are not of its graph") {
  const sched::CostTable three(3, 2, 1.0);
  CHECK_THROWS_WITH(plan::place_async(chain(), three, sched::DeviceLinks::unified_memory(2, 0.0), true),
                    Catch::Contains("costs of 3 tasks on 2 devices"));
}
