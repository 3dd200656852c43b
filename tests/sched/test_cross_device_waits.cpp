// The minimal set of cross-device waits for in-order queues.
#include <fmt/format.h>
#include <catch2/catch.hpp>

#include "sched/schedule.hpp"

using namespace atssim::sched;

namespace {

TaskGraph tasks(int n) {
  TaskGraph g;
  for (int i = 0; i < n; ++i) g.add_task({fmt::format("t{}", i), 0, -1, -1});
  return g;
}

}  // namespace

TEST_CASE("Same-device edges need no wait", "[waits]") {
  TaskGraph g = tasks(2);
  g.add_edge(0, 1);
  const Schedule s = assemble_schedule(2, {{{0, 0, 1}, {1, 1, 2}}, {}});
  CHECK(s.cross_device_waits(g).empty());
}

TEST_CASE("Tasks in a row on one queue reading one producer share one wait", "[waits]") {
  // u on device 0 feeds v1, v2, v3 that run in a row on device 1.
  TaskGraph g = tasks(4);
  g.add_edge(0, 1);
  g.add_edge(0, 2);
  g.add_edge(0, 3);
  const Schedule s = assemble_schedule(4, {{{0, 0, 1}}, {{1, 1, 2}, {2, 2, 3}, {3, 3, 4}}});
  CHECK(s.cross_device_waits(g) == std::vector<Wait>{{0, 0, 1, 1}});
}

TEST_CASE("A wait implied by an earlier wait on a later producer is dropped", "[waits]") {
  // Device 0 runs u1 then u2. v1 (device 1) waits for u2; v2, after v1,
  // reads u1, which finished before u2 on the in-order queue.
  TaskGraph g = tasks(4);
  g.add_edge(1, 2);
  g.add_edge(0, 3);
  const Schedule s = assemble_schedule(4, {{{0, 0, 1}, {1, 1, 2}}, {{2, 2, 3}, {3, 3, 4}}});
  CHECK(s.cross_device_waits(g) == std::vector<Wait>{{1, 0, 2, 1}});
}

TEST_CASE("A later task reading a later producer needs its own wait", "[waits]") {
  // v1 reads u1, v2 reads u2 (after u1): the first wait does not cover u2.
  TaskGraph g = tasks(4);
  g.add_edge(0, 2);
  g.add_edge(1, 3);
  const Schedule s = assemble_schedule(4, {{{0, 0, 1}, {1, 1, 2}}, {{2, 1, 2}, {3, 2, 3}}});
  CHECK(s.cross_device_waits(g) == std::vector<Wait>{{0, 0, 2, 1}, {1, 0, 3, 1}});
}

TEST_CASE("Of two inputs on one queue only the later needs a wait", "[waits]") {
  TaskGraph g = tasks(3);
  g.add_edge(0, 2);
  g.add_edge(1, 2);
  const Schedule s = assemble_schedule(3, {{{0, 0, 1}, {1, 1, 2}}, {{2, 2, 3}}});
  CHECK(s.cross_device_waits(g) == std::vector<Wait>{{1, 0, 2, 1}});
}

TEST_CASE("A wait implied through a third queue is dropped", "[waits]") {
  // a (device 0) → b (device 1) → c (device 2), and a → c: c's wait for b
  // already orders it after a.
  TaskGraph g = tasks(3);
  g.add_edge(0, 1);
  g.add_edge(1, 2);
  g.add_edge(0, 2);
  const Schedule s = assemble_schedule(3, {{{0, 0, 1}}, {{1, 1, 2}}, {{2, 2, 3}}});
  CHECK(s.cross_device_waits(g) == std::vector<Wait>{{0, 0, 1, 1}, {1, 1, 2, 2}});
}

TEST_CASE("Each device's queue waits for the other when data goes both ways", "[waits]") {
  // Ping-pong: 0 (dev 0) → 1 (dev 1) → 2 (dev 0) → 3 (dev 1).
  TaskGraph g = tasks(4);
  g.add_edge(0, 1);
  g.add_edge(1, 2);
  g.add_edge(2, 3);
  const Schedule s = assemble_schedule(4, {{{0, 0, 1}, {2, 2, 3}}, {{1, 1, 2}, {3, 3, 4}}});
  CHECK(s.cross_device_waits(g) == std::vector<Wait>{{1, 1, 2, 0}, {0, 0, 1, 1}, {2, 0, 3, 1}});
}
