#include <catch2/catch.hpp>

#include "sched/device_timeline.hpp"

using namespace atssim::sched;

TEST_CASE("A task fills the first idle gap that fits it", "[timeline]") {
  DeviceTimeline t;
  t.reserve(0, 2);
  t.reserve(5, 6);   // gap [2, 5)
  t.reserve(7, 10);  // gap [6, 7)
  CHECK(t.earliest_start(0, 3, true) == 2);
  CHECK(t.earliest_start(3, 3, true) == 10);  // [3, 5) too short, [6, 7) too
  CHECK(t.earliest_start(5.5, 1, true) == 6);
  CHECK(t.earliest_start(0, 3, false) == 10);
  CHECK(t.end() == 10);
}

TEST_CASE("Nothing starts before the device's ready time", "[timeline]") {
  DeviceTimeline t(4.0);
  CHECK(t.earliest_start(0, 1, true) == 4);
  CHECK(t.earliest_start(6, 1, true) == 6);
}

TEST_CASE("Gaps shorter than the shortest task are dropped", "[timeline]") {
  DeviceTimeline t(0.0, 2.0);
  t.reserve(1, 3);  // [0, 1) is unusable
  t.reserve(6, 7);  // [3, 6) is kept
  CHECK(t.gap_count() == 2);
  CHECK(t.earliest_start(0, 2, true) == 3);
}

TEST_CASE("Reserving outside an idle gap is an error", "[timeline]") {
  DeviceTimeline t;
  t.reserve(0, 2);
  CHECK_THROWS(t.reserve(1, 3));
}
