#include <catch2/catch.hpp>

#include "sched/cost_model.hpp"
#include "sched/profile_costs.hpp"

using namespace atssim::sched;

namespace {

// Two tasks in one substep on `device`: task 0 from 0 to a, task 1 from
// a + gap to a + gap + b.
std::vector<TaskTiming> substep(DeviceId device, double a, double gap, double b) {
  return {{0, device, 0.0, a}, {1, device, a + gap, a + gap + b}};
}

}  // namespace

TEST_CASE("a profiled task costs the trimmed mean of its substeps after the warm-up") {
  // One warm-up (100 ms: a first launch compiles) and five substeps on
  // device 0. Task 0 took 1, 2, 3, 4, 50 ms: trimming 20 % at each end drops
  // 1 and 50, leaving (2 + 3 + 4) / 3 = 3. Task 1 counts from the end of
  // task 0 (the 0.5 ms gap is its cost): 1.5 every time.
  ProfileCosts profile(2, 1);
  profile.substep_alone(0, substep(0, 100.0, 0.5, 100.0));
  for (double a : {1.0, 2.0, 3.0, 4.0, 50.0}) profile.substep_alone(0, substep(0, a, 0.5, 1.0));
  const CostTable costs = profile.costs();
  CHECK(costs.at(0, 0) == Approx(3.0));
  CHECK(costs.at(1, 0) == Approx(1.5));
}

TEST_CASE("a reported launch gap is taken off every task's profiled cost, down to the floor") {
  // Device 1 was timed by per-launch events, with a gap of 0.5 ms between
  // two launches: task 0's 2 ms become 1.5 ms, task 1's 0.5 + 0.25 ms become
  // 0.25 ms; device 0 reported no gap. A gap longer than a task leaves 1e-6.
  ProfileCosts profile(2, 2, {.warmup = 0});
  profile.substep_alone(0, substep(0, 2.0, 0.5, 0.25));
  profile.substep_alone(1, substep(1, 2.0, 0.5, 0.25));
  profile.launch_gap(1, 0.5);
  CostTable costs = profile.costs();
  CHECK(costs.at(0, 0) == Approx(2.0));
  CHECK(costs.at(1, 0) == Approx(0.75));
  CHECK(costs.at(0, 1) == Approx(1.5));
  CHECK(costs.at(1, 1) == Approx(0.25));
  profile.launch_gap(1, 5.0);
  costs = profile.costs();
  CHECK(costs.at(0, 1) == 1e-6);
}

TEST_CASE("a task never timed on a device costs the floor there") {
  ProfileCosts profile(3, 1, {.warmup = 0});
  profile.substep_alone(0, substep(0, 2.0, 0.0, 1.0));
  CHECK(profile.costs().at(2, 0) == 1e-6);
}

TEST_CASE("timings of a task outside the table, or of another device, are a bug") {
  ProfileCosts profile(1, 1, {.warmup = 0});
  CHECK_THROWS_WITH(profile.substep_alone(0, substep(0, 1.0, 0.0, 1.0)), Catch::Contains("task 1 timed on device 0"));
  CHECK_THROWS_WITH(profile.substep_alone(1, {}), Catch::Contains("a substep on device 1 of 1"));
}

TEST_CASE("a frame's makespan is its latest task end, else its longest launch per substep") {
  const std::vector<TaskTiming> timings{{0, 0, 0.0, 1.0}, {1, 1, 0.5, 2.5}, {2, 0, 1.0, 2.0}};
  const std::vector<LaunchTiming> launches{{0, 4, 8.0}, {1, 2, 6.0}};
  CHECK(measured_makespan_ms(timings, launches) == 2.5);
  CHECK(measured_makespan_ms({}, launches) == 3.0);  // 8 / 4 and 6 / 2
  CHECK(measured_makespan_ms({}, {}) == 0.0);
}
