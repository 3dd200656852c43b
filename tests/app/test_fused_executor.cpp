// The fused executor against the events executor (the reference), and its
// refusals: an unknown task function, a wait that never completes.
#include <catch2/catch.hpp>

#include <algorithm>
#include <chrono>
#include <string>

#include "app/execution.hpp"
#include "app/simulation.hpp"
#include "device/device_set.hpp"
#include "device/plan_executor.hpp"
#include "scene/scene_loader.hpp"
#include "solver/method_registry.hpp"
#include "support/methods.hpp"
#include "support/scenes.hpp"
#include "util/error.hpp"

using namespace atssim;

namespace {

struct Ran {
  std::vector<float> positions;
  std::vector<int> first_tasks_per_device;  // of the schedule the first half ran with
  std::vector<int> tasks_per_device;        // of the schedule the second half ran with
  std::vector<sched::DeviceId> assignment;
};

std::vector<int> count_per_device(const std::vector<sched::DeviceId>& assignment, std::size_t devices) {
  std::vector<int> n(devices, 0);
  for (sched::DeviceId d : assignment) ++n[d];
  return n;
}

// Async and HEFT place by profiled costs and the measured hop, which differ
// from one execution to the next (under load HEFT may keep everything on
// one device): given equal costs and a fixed hop, HEFT uses both devices
// (tests/app/test_async.cpp) and the two executions place alike. HEFT's
// later schedule, after the refit from measured times, may differ.
Ran run(const device::DeviceSet& devices, const plan::SubstepPlan& plan, app::ScheduleMode mode,
        device::ExecutorKind kind, int substeps) {
  app::ExecutionOptions options;
  options.mode = mode;
  options.executor = kind;
  options.profile_repetitions = 2;
  if (mode == app::ScheduleMode::async || mode == app::ScheduleMode::heft) {
    const std::size_t tasks =
        mode == app::ScheduleMode::async ? plan.graph.size() : app::cut_for_mode(plan, mode, 2).graph.size();
    options.placement_costs = sched::CostTable(tasks, 2, 1.0);
    options.placement_links = sched::DeviceLinks::unified_memory(2, 0.01);
  }
  app::Execution e = app::prepare_execution(devices, plan, options);
  REQUIRE(e.executor->kind() == kind);
  const std::vector<int> first = count_per_device(e.assignment, devices.size());
  e.executor->run_substeps(substeps, true);
  app::refit_and_reschedule(e, options);  // a heft schedule may change, a split cut move: the result must not
  e.executor->run_substeps(substeps);
  Ran r;
  e.executor->read_positions(r.positions);
  r.first_tasks_per_device = first;
  r.tasks_per_device = count_per_device(e.assignment, devices.size());
  r.assignment = e.assignment;
  return r;
}

// The cloth and soft box of test::cloth_and_box_yaml; where the method has
// contact, also a kinematic sphere collider the cloth falls on and contact
// between the surfaces (cloth-solid, self); explicit gets its stable step.
std::string scene_for(const solver::MethodDescription& method) {
  std::string yaml = test::cloth_and_box_yaml(std::string(method.name), 14);
  if (method.colliders) {
    yaml +=
        "colliders:\n"
        "  - {type: sphere, radius: 0.1, center: [0, 0.2, 0], velocity: [0, 0.5, 0], friction: 0.3}\n"
        "contact: {self: true, thickness: 0.01}\n";
  } else {
    const std::string steps = "substeps: 2,";
    yaml.replace(yaml.find(steps), steps.size(), "substeps: 64,");
  }
  return yaml;
}

}  // namespace

TEST_CASE(
    "fused execution equals events execution bit for bit, and two devices give the one-device bits, for every method "
    "and schedule",
    "[fused]") {
  const std::string method = GENERATE(from_range(test::method_names()));
  const solver::MethodDescription& description = solver::method(method);
  const auto scene = scene::parse_scene(scene_for(description), "s.yaml", ".");
  const plan::SubstepPlan plan = app::substep_plan_for(scene);
  std::vector<app::ScheduleMode> modes = {app::ScheduleMode::single, app::ScheduleMode::split, app::ScheduleMode::heft};
  if (description.gauss_seidel) modes.push_back(app::ScheduleMode::async);
  std::vector<float> start;
  for (const auto& p : plan.buffers) {
    if (p.role == plan::BufferRole::positions) start = plan::values_of<float>(p.initial);
  }
  std::vector<float> one_device;
  for (const app::ScheduleMode mode : modes) {
    INFO(method << " " << app::to_string(mode));
    const auto devices = device::DeviceSet::open(mode == app::ScheduleMode::single ? "cpu" : "cpu/2");
    const int substeps = description.colliders ? 3 : 48;  // explicit: 16 of its substeps are one of the others'
    const Ran events = run(devices, plan, mode, device::ExecutorKind::events, substeps);
    const Ran fused = run(devices, plan, mode, device::ExecutorKind::fused, substeps);
    if (mode == app::ScheduleMode::async) REQUIRE(events.assignment == fused.assignment);
    REQUIRE(events.positions.size() == fused.positions.size());
    std::size_t differ = 0;
    for (std::size_t i = 0; i < events.positions.size(); ++i) differ += events.positions[i] != fused.positions[i];
    CHECK(differ == 0);
    // The substeps did work: the free cloth corner fell.
    CHECK(std::abs(fused.positions[3 * 13 + 1] - start[4 * 13 + 1]) > 1e-4);  // the plan keeps x, y, z, w
    if (mode == app::ScheduleMode::single) {
      one_device = events.positions;
      continue;
    }
    // Both devices ran tasks where the schedule guarantees it: split cuts
    // every block between them; async with equal placement costs overlaps
    // the chains of two Gauss-Seidel kinds (XPBD: stretch and bending), but
    // keeps a method with one kind (VBD's vertex colors: each kind keeps its
    // order, paper §4.1.2) a serial chain on one device, the one-device bits.
    // HEFT given equal costs and a fixed hop places the first half's
    // tasks on both (its second half follows the measured times).
    const bool overlapping = mode == app::ScheduleMode::async && test::gauss_seidel_kinds(plan) > 1;
    const bool both = mode == app::ScheduleMode::split || overlapping;
    for (const Ran* r : {&events, &fused}) {
      INFO("tasks per device " << r->tasks_per_device[0] << ", " << r->tasks_per_device[1] << " (first half "
                               << r->first_tasks_per_device[0] << ", " << r->first_tasks_per_device[1] << ")");
      if (both) {
        CHECK(r->tasks_per_device[0] > 0);
        CHECK(r->tasks_per_device[1] > 0);
      } else if (mode == app::ScheduleMode::heft) {
        CHECK(r->first_tasks_per_device[0] > 0);
        CHECK(r->first_tasks_per_device[1] > 0);
      } else if (mode == app::ScheduleMode::async) {
        CHECK(std::min(r->tasks_per_device[0], r->tasks_per_device[1]) == 0);
      }
    }
    // split and heft cut or place the same iteration: the one-device bits;
    // so does async where it stays one chain. Overlapping async is another
    // iteration (tests/app/test_async.cpp).
    if (!overlapping) {
      std::size_t moved = 0;
      for (std::size_t i = 0; i < events.positions.size(); ++i) moved += events.positions[i] != one_device[i];
      CHECK(moved == 0);
    }
  }
}

TEST_CASE("the fused executor times every task of a recorded substep on one clock", "[fused][fast]") {
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
  // sub-devices share one cycle counter. Up to the counter's own precision:
  // the dispatcher stamps with rdtsc (__builtin_readcyclecounter), which the
  // CPU may run ahead of the wait's load that precedes it (OpenCL C has no
  // serializing fence), and two vCPUs' counters may differ by some tens of
  // ns. Under load a consumer's stamp came 20 and 30 ns before its
  // producer's (a full ctest, 5 December). Two clocks with zeros of their
  // own would differ by the devices' launch skew, tens of microseconds and
  // more.
  constexpr double kClockPrecisionMs = 1e-3;
  for (sched::TaskId t = 0; t < e.plan().graph.size(); ++t) {
    for (const auto& edge : e.plan().graph.successors(t)) {
      CHECK(start[edge.to] >= end[edge.from] - kClockPrecisionMs);
    }
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

TEST_CASE("an executor refuses a launch of a task function its program does not declare", "[fused][fast]") {
  // The colors ordering: launch [1][0] is a stretch block's xpbd_stretch (7 arguments).
  const auto scene = scene::parse_scene(test::hanging_cloth_yaml(6) + "solver: {ordering: colors}\n", "s.yaml", ".");
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

TEST_CASE("a fused wait that never completes ends in an error naming the device and task, not a hang",
          "[fused][fast]") {
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
