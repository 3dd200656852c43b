// HEFT over links priced by size (non-unified memory, paper §3.3.1): a
// fork-join graph worked out by hand.
//
//        A            task  cost on d0  cost on d1
//       / \            A        1           1
//      B   C           B        4           4
//       \ /            C        4           4
//        D             D        1           1
//
// Every edge carries 40 000 bytes; a hop costs c = 0.02 ms + bytes · ms/byte.
// Ranks: B and C tie (4 + c + 1), B goes first by id. A → d0 (ends 1),
// B → d0 (ends 5). C: on d0 it ends 9, on d1 it ends 1 + c + 4 = 5 + c, so
// it moves to d1 when c < 4. D then ends at max(5, 5 + 2c) + 1 on d0 or
// max(5 + c, 5 + c) + 1 = 6 + c on d1. Makespan: 6 + c when c < 4, else
// 10 with everything on d0 (the bytes cost more than the second device
// saves).
#include <catch2/catch.hpp>

#include "classic_graphs.hpp"
#include "sched/heft.hpp"

using namespace atssim::sched;

namespace {

test::Problem fork_join(double latency_ms, double ms_per_byte) {
  const double bytes = 40000.0;
  test::Problem p = test::make_problem({"A", "B", "C", "D"}, {{1, 1}, {4, 4}, {4, 4}, {1, 1}},
                                       {{0, 1, bytes}, {0, 2, bytes}, {1, 3, bytes}, {2, 3, bytes}});
  p.links = DeviceLinks::weighted(2, latency_ms, ms_per_byte);
  return p;
}

}  // namespace

TEST_CASE("HEFT splits a fork over a fast link and keeps it on one device over a slow one", "[heft]") {
  // clang-format off
  const auto [ms_per_byte, hop, makespan, c_device, d_device] = GENERATE(table<double, double, double, DeviceId, DeviceId>({
      {2.0e-6,   0.10,  6.10, 1, 1},   // fast: the two branches run side by side
      {7.45e-5,  3.00,  9.00, 1, 1},   // slower: still worth it, by 1 ms
      {1.25e-4,  5.02, 10.00, 0, 0},   // slow: the copies cost more than the work saved
  }));
  // clang-format on
  CAPTURE(ms_per_byte);
  const test::Problem p = fork_join(0.02, ms_per_byte);
  CHECK(p.links.comm_ms(40000.0, 0, 1) == Approx(hop));
  const Schedule s = schedule_heft(p.graph, p.costs, p.links);
  CHECK(s.validate(p.graph, p.costs, p.links).empty());
  CHECK(s.device_of(0) == 0);
  CHECK(s.device_of(1) == 0);
  CHECK(s.device_of(2) == c_device);
  CHECK(s.device_of(3) == d_device);
  CHECK(s.makespan_ms == Approx(makespan));
}

TEST_CASE("The same fork with a fixed hop (unified memory) ignores the bytes", "[heft]") {
  test::Problem p = fork_join(0.0, 0.0);
  p.links = DeviceLinks::unified_memory(2, 0.1);
  CHECK(p.links.comm_ms(40000.0, 0, 1) == Approx(0.1));
  CHECK(p.links.comm_ms(4.0e9, 0, 1) == Approx(0.1));
  const Schedule s = schedule_heft(p.graph, p.costs, p.links);
  CHECK(s.device_of(2) == 1);
  CHECK(s.makespan_ms == Approx(6.1));
}

TEST_CASE("HEFT cannot see the copies its choices force later, one device is kept when it ends sooner", "[heft]") {
  // The fork again, with 1 000 bytes on A→B, A→C and 250 000 on B→D, C→D
  // at 4e-5 ms per byte (no latency): 0.04 ms into the branches, 10 ms out.
  // HEFT: A, B on d0 (end 5); C on d1 ends 1 + 0.04 + 4 = 5.04 < 9 on d0;
  // D then ends max(5, 5.04 + 10) + 1 = 16.04 on d0 or
  // max(5 + 10, 5.04) + 1 = 16 on d1: makespan 16. All on d0: 1+4+4+1 = 10.
  test::Problem p = test::make_problem({"A", "B", "C", "D"}, {{1, 1}, {4, 4}, {4, 4}, {1, 1}},
                                       {{0, 1, 1000.0}, {0, 2, 1000.0}, {1, 3, 250000.0}, {2, 3, 250000.0}});
  p.links = DeviceLinks::weighted(2, 0.0, 4.0e-5);
  const Schedule heft = schedule_heft(p.graph, p.costs, p.links);
  CHECK(heft.device_of(2) == 1);
  CHECK(heft.makespan_ms == Approx(16.0));
  const Schedule best = schedule_heft_or_one_device(p.graph, p.costs, p.links);
  CHECK(best.validate(p.graph, p.costs, p.links).empty());
  CHECK(best.makespan_ms == Approx(10.0));
  for (TaskId t = 0; t < 4; ++t) CHECK(best.device_of(t) == 0);
  REQUIRE(best.devices.size() == 2);
  CHECK(best.devices[1].empty());
  // Over a fast link HEFT's own schedule wins and is kept.
  p.links = DeviceLinks::weighted(2, 0.0, 4.0e-8);
  const Schedule fast = schedule_heft_or_one_device(p.graph, p.costs, p.links);
  CHECK(fast.device_of(2) == 1);
  CHECK(fast.makespan_ms == Approx(6.01).margin(0.01));
}
