#include <catch2/catch.hpp>

#include <fmt/format.h>

#include "sched/sync_map.hpp"

using namespace atssim;
using namespace atssim::sched;

namespace {

// Builds a schedule from explicit lanes: {task, start, finish} per device.
Schedule lanes(std::size_t tasks, std::vector<std::vector<Slot>> devices) {
  return assemble_schedule(tasks, std::move(devices));
}

TaskGraph chain(int n) {
  TaskGraph g;
  for (int i = 0; i < n; ++i) g.add_task({fmt::format("t{}", i), 0, i, 0});
  for (int i = 1; i < n; ++i) g.add_edge(i - 1, i);
  return g;
}

}  // namespace

TEST_CASE("a dependency across devices is always merged, the first helper merge being a copy") {
  // t0 (main 0) -> t1 (helper 1) -> t2 (main 0)
  const TaskGraph g = chain(3);
  const Schedule s = lanes(3, {{{0, 0, 1}, {2, 3, 4}}, {{1, 1.5, 2.5}}});
  const SyncMap m = build_sync_map(g, s, DeviceLinks::unified_memory(2, 0.1), 0, {false});
  REQUIRE(m.merges.size() == 2);
  const bool helper_first = m.merges[0].consumer_device == 1;
  const Merge& helper = m.merges[helper_first ? 0 : 1];
  const Merge& main = m.merges[helper_first ? 1 : 0];
  CHECK(helper.consumer == 1);
  CHECK(helper.producer == 0);
  CHECK(helper.start == kNoTask);  // no common start yet: copy the main result
  CHECK(main.consumer == 2);
  CHECK(main.producer == 1);
  CHECK(main.start == 0);  // the helper's copy descends from t0's result
}

TEST_CASE("only dependencies are merged unless the latest results are asked for") {
  // Two independent chains: a0 -> a1 on device 0, b0 -> b1 on device 1, after a root r on 0.
  TaskGraph g;
  for (const char* n : {"r", "a0", "a1", "b0", "b1"}) g.add_task({n, 0, 0, 0});
  g.add_edge(0, 1);
  g.add_edge(1, 2);
  g.add_edge(0, 3);
  g.add_edge(3, 4);
  const Schedule s = lanes(5, {{{0, 0, 1}, {1, 1, 2}, {2, 2, 3}}, {{3, 1.2, 2.2}, {4, 2.2, 3.2}}});
  const DeviceLinks links = DeviceLinks::unified_memory(2, 0.05);
  const SyncMap deps = build_sync_map(g, s, links, 0, {false});
  CHECK(deps.merges.size() == 1);  // b0 needs r
  const SyncMap latest = build_sync_map(g, s, links, 0, {true});
  // b0 takes r, b1 takes a0 (done at 2 ≤ 2.2 - 0.05? no: 2.05 ≤ 2.2 yes), a1 takes nothing new
  // (b0 ends at 2.2 > 2), and the main device merges nothing it could not have.
  bool b1_takes_a0 = false;
  for (const Merge& m : latest.merges) {
    CHECK(m.producer != m.consumer);
    if (m.consumer == 4 && m.producer == 1) b1_takes_a0 = true;
    if (m.consumer_device == 0) CHECK(s.slot(m.producer).finish_ms + 0.05 <= s.slot(m.consumer).start_ms);
  }
  CHECK(b1_takes_a0);
  CHECK(latest.merges.size() > deps.merges.size());
}

TEST_CASE("a helper's start point moves with every main result it merges") {
  // main: m0 m1 m2 ; helper: h0 (needs m0), h1 (needs m1); main's m2 needs h1.
  TaskGraph g;
  for (const char* n : {"m0", "m1", "m2", "h0", "h1"}) g.add_task({n, 0, 0, 0});
  g.add_edge(0, 1);
  g.add_edge(1, 2);
  g.add_edge(0, 3);
  g.add_edge(3, 4);
  g.add_edge(1, 4);
  g.add_edge(4, 2);
  const Schedule s = lanes(5, {{{0, 0, 1}, {1, 1, 2}, {2, 5, 6}}, {{3, 1.1, 2}, {4, 2.1, 4}}});
  const SyncMap m = build_sync_map(g, s, DeviceLinks::unified_memory(2, 0.05), 0, {false});
  std::vector<Merge> helper, main;
  for (const Merge& x : m.merges) (x.consumer_device == 0 ? main : helper).push_back(x);
  REQUIRE(helper.size() == 2);
  CHECK(helper[0].start == kNoTask);
  CHECK(helper[1].producer == 1);
  CHECK(helper[1].start == 0);  // the segment that began with m0's result
  REQUIRE(main.size() == 1);
  CHECK(main[0].producer == 4);
  CHECK(main[0].start == 1);  // h1 ran in the segment that began with m1's result
}
