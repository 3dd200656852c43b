// The fused executor against the events executor (the reference), and its
// refusals: an unknown task function, a wait that never completes.
#include <catch2/catch.hpp>

#include <chrono>
#include <string>

#include "app/execution.hpp"
#include "app/simulation.hpp"
#include "device/device_set.hpp"
#include "device/plan_executor.hpp"
#include "scene/scene_loader.hpp"
#include "support/methods.hpp"
#include "support/scenes.hpp"
#include "util/error.hpp"

using namespace atssim;

namespace {

std::vector<float> run(const device::DeviceSet& devices, const plan::SubstepPlan& plan, app::ScheduleMode mode,
                       device::ExecutorKind kind, int substeps) {
  app::ExecutionOptions options;
  options.mode = mode;
  options.executor = kind;
  options.profile_repetitions = 2;
  app::Execution e = app::prepare_execution(devices, plan, options);
  REQUIRE(e.executor->kind() == kind);
  e.executor->run_substeps(substeps, true);
  app::refit_and_reschedule(e, options);  // a heft schedule may change: the result must not
  e.executor->run_substeps(substeps);
  std::vector<float> xyz;
  e.executor->read_positions(xyz);
  return xyz;
}

}  // namespace

TEST_CASE("fused execution equals events execution bit for bit for every method and schedule", "[fused]") {
  const std::string method =
      GENERATE(from_range(test::methods_taking([](const std::string& m) { return test::cloth_and_box_yaml(m, 14); })));
  const auto mode = GENERATE(app::ScheduleMode::single, app::ScheduleMode::split, app::ScheduleMode::heft);
  const auto scene = scene::parse_scene(test::cloth_and_box_yaml(method, 14), "s.yaml", ".");
  const plan::SubstepPlan plan = app::substep_plan_for(scene);
  const auto devices = device::DeviceSet::open(mode == app::ScheduleMode::single ? "cpu" : "cpu/2");
  const std::vector<float> events = run(devices, plan, mode, device::ExecutorKind::events, 3);
  const std::vector<float> fused = run(devices, plan, mode, device::ExecutorKind::fused, 3);
  INFO(method << " " << app::to_string(mode));
  REQUIRE(events.size() == fused.size());
  std::size_t differ = 0;
  for (std::size_t i = 0; i < events.size(); ++i) differ += events[i] != fused[i] ? 1 : 0;
  CHECK(differ == 0);
  // The substeps did work: the free cloth corner fell.
  std::vector<float> start;
  for (const auto& p : app::substep_plan_for(scene).buffers) {
    if (p.role == plan::BufferRole::positions) start = plan::values_of<float>(p.initial);
  }
  CHECK(std::abs(fused[3 * 13 + 1] - start[4 * 13 + 1]) > 1e-4);
}

TEST_CASE("the fused executor times every task of a recorded substep on one clock", "[fused]") {
  const auto scene = scene::parse_scene(test::hanging_cloth_yaml(12), "s.yaml", ".");
  const auto devices = device::DeviceSet::open("cpu/2");
  app::ExecutionOptions options;
  options.mode = app::ScheduleMode::split;
  options.executor = device::ExecutorKind::fused;
  app::Execution e = app::prepare_execution(devices, app::substep_plan_for(scene), options);
  REQUIRE(e.executor->has_task_clock());
  e.executor->run_substeps(2, true);
  const auto timings = e.executor->recorded();
  CHECK(timings.size() == e.plan().graph.size());
  std::vector<double> end(e.plan().graph.size(), -1.0), start(e.plan().graph.size(), -1.0);
  for (const auto& t : timings) {
    CHECK(t.finish_ms >= t.start_ms);
    start[t.task] = t.start_ms;
    end[t.task] = t.finish_ms;
  }
  // A consumer starts after its producer ended, on either device: the two
  // sub-devices share one cycle counter.
  for (sched::TaskId t = 0; t < e.plan().graph.size(); ++t) {
    for (const auto& edge : e.plan().graph.successors(t)) CHECK(start[edge.to] >= end[edge.from]);
  }
}

TEST_CASE("without a task clock the fused executor times launches, and its costs follow them", "[fused]") {
  const auto scene = scene::parse_scene(test::hanging_cloth_yaml(12), "s.yaml", ".");
  const plan::SubstepPlan plan = app::substep_plan_for(scene);
  const auto devices = device::DeviceSet::open("cpu/2");
  app::ExecutionOptions options;
  options.mode = app::ScheduleMode::split;
  options.executor = device::ExecutorKind::fused;
  options.task_clock = false;
  options.profile_repetitions = 2;
  app::Execution e = app::prepare_execution(devices, plan, options);
  REQUIRE_FALSE(e.executor->has_task_clock());
  for (std::size_t t = 0; t < e.plan().graph.size(); ++t) CHECK(e.costs.costs().at(t, 0) > 0.0);
  e.executor->run_substeps(4, true);
  const app::FrameMeasurement m = app::refit_and_reschedule(e, options);
  CHECK(m.timings.empty());
  const auto launches = e.executor->launches();
  REQUIRE(launches.size() == 2);
  for (const auto& l : launches) {
    CHECK(l.substeps == 4);
    CHECK(l.ms > 0.0);
  }
  CHECK(m.makespan_ms > 0.0);
  // The same bits as with the clock: timing does not touch the simulation.
  e.executor->run_substeps(2);
  std::vector<float> without;
  e.executor->read_positions(without);
  options.task_clock = true;
  app::Execution with_clock = app::prepare_execution(devices, plan, options);
  with_clock.executor->run_substeps(6);
  std::vector<float> with;
  with_clock.executor->read_positions(with);
  CHECK(with == without);
}

TEST_CASE("an executor refuses a launch of a task function its program does not declare", "[fused]") {
  const auto scene = scene::parse_scene(test::hanging_cloth_yaml(6), "s.yaml", ".");
  plan::SubstepPlan plan = app::substep_plan_for(scene);
  const auto devices = device::DeviceSet::open("cpu");
  SECTION("an unknown name") {
    plan.launches[1][0].function = "xpbd_strech";
    for (auto kind : {device::ExecutorKind::fused, device::ExecutorKind::events}) {
      device::ExecutorOptions o;
      o.kind = kind;
      CHECK_THROWS_WITH(device::PlanExecutor(devices, plan, o), Catch::Contains("'xpbd_strech'") &&
                                                                    Catch::Contains("program 'xpbd'") &&
                                                                    Catch::Contains("xpbd_stretch"));
    }
  }
  SECTION("a wrong argument list") {
    plan.launches[1][0].args.pop_back();
    CHECK_THROWS_WITH(device::PlanExecutor(devices, plan), Catch::Contains("takes 7"));
    plan.launches[1][0].args.push_back(plan::KernelArg::of_int(1));  // its last parameter is the float 1/h
    CHECK_THROWS_WITH(device::PlanExecutor(devices, plan), Catch::Contains("expects a float"));
  }
  SECTION("a declared write to a buffer it does not write through") {
    // The copies between memories follow the declaration: a stale one (a
    // buffer renamed in the arguments, not in the writes) must not run.
    auto& launch = plan.launches[1][0];
    REQUIRE_FALSE(launch.writes.empty());
    launch.writes.front().buffer = plan.buffer(plan::BufferRole::velocities);
    CHECK_THROWS_WITH(device::PlanExecutor(devices, plan), Catch::Contains("declares a write to buffer"));
  }
}

TEST_CASE("a fused wait that never completes ends in an error naming the device and task, not a hang", "[fused]") {
  const std::string spec = GENERATE("cpu/2", "cpu");  // across sub-devices; between the work-groups of one device
  const auto scene = scene::parse_scene(test::hanging_cloth_yaml(8), "s.yaml", ".");
  const auto devices = device::DeviceSet::open(spec);
  plan::SubstepPlan plan = app::substep_plan_for(scene);
  device::ExecutorOptions o;
  o.kind = device::ExecutorKind::fused;
  o.wait_timeout_s = 0.3;
  o.never_publish = 2;  // a stretch block of the first iteration
  device::PlanExecutor exec(devices, plan, o);
  if (devices.size() == 2) {
    // Every task on device 0 but task 3 on device 1: it waits for task 2.
    std::vector<std::vector<sched::Slot>> lanes(2);
    double t = 0.0;
    for (sched::TaskId id : plan.graph.topological_order()) {
      lanes[id == 3 ? 1 : 0].push_back({id, t, t + 1.0});
      t += 1.0;
    }
    const sched::Schedule s = sched::assemble_schedule(plan.graph.size(), std::move(lanes));
    const auto waits = s.cross_device_waits(plan.graph);
    exec.run_schedule(s, waits);
  }
  const auto begin = std::chrono::steady_clock::now();
  exec.run_substeps(2);
  try {
    exec.finish();
    FAIL("the wait completed");
  } catch (const Error& e) {
    INFO(e.what());
    CHECK(e.exit_code() == 1);
    CHECK(std::string(e.what()).find("no task finished on any device for 0.3 s") != std::string::npos);
    CHECK(std::string(e.what()).find("'" + plan.graph.task(2).name + "'") != std::string::npos);
  }
  const double s = std::chrono::duration<double>(std::chrono::steady_clock::now() - begin).count();
  CHECK(s < 5.0);
  CHECK_THROWS_AS(exec.run_substeps(1), Error);  // the run cannot go on after a failed wait
}
