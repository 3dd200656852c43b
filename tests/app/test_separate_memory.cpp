// Devices that share no memory (`memory: separate`): every device holds its
// own copy of the state and the transfer plan moves what another device
// needs. The reference is the same schedule on devices that share one
// memory: the copies must reproduce it bit for bit.
#include <catch2/catch.hpp>

#include <cmath>
#include <span>
#include <string>

#include "app/execution.hpp"
#include "app/simulation.hpp"
#include "device/device_set.hpp"
#include "device/plan_executor.hpp"
#include "kernels/embedded_programs.hpp"
#include "plan/element_sets.hpp"
#include "scene/scene_loader.hpp"
#include "support/methods.hpp"
#include "support/scenes.hpp"

using namespace atssim;

namespace {

struct Outcome {
  std::vector<float> xyz;
  std::size_t bytes = 0;          // counted by the executor over the measured substeps
  std::size_t planned_bytes = 0;  // the transfer plan's bytes per substep
  std::size_t written_bytes = 0;  // what the tasks write in a substep, each task counted alone
  std::vector<sched::CopyTiming> copies;
};

// The bytes every task of a substep writes, from the launches' declared
// spans: with two devices each write needs to move at most once, to the
// other one.
// (`sizes`: the buffers' sizes; an executor's plan has released its
// initial contents.)
std::size_t written_bytes(const plan::SubstepPlan& plan, std::span<const std::size_t> sizes) {
  const auto tasks = kernels::program_tasks(plan.program);
  std::size_t bytes = 0;
  for (sched::TaskId t = 0; t < plan.graph.size(); ++t) {
    for (const plan::KernelLaunch& launch : plan.launches[t]) {
      std::vector<char> writable(launch.args.size(), 0);
      for (const auto& sig : tasks) {
        if (sig.name != launch.function) continue;
        for (std::size_t a = 0; a < writable.size() && a < sig.access.size(); ++a) writable[a] = sig.access[a] == 'w';
      }
      bytes += plan::written_elements(launch, writable, sizes).bytes();
    }
  }
  return bytes;
}

Outcome run(const device::DeviceSet& devices, const plan::SubstepPlan& plan, app::ScheduleMode mode, int substeps) {
  app::ExecutionOptions options;
  options.mode = mode;
  options.executor = device::ExecutorKind::events;
  options.profile_repetitions = 2;
  app::Execution e = app::prepare_execution(devices, plan, options);
  e.executor->run_substeps(substeps, true);
  app::refit_and_reschedule(e, options);  // a heft schedule may change: the result must not
  e.executor->take_bytes_moved();
  e.executor->run_substeps(substeps, true);
  Outcome o;
  o.bytes = e.executor->take_bytes_moved();
  if (const plan::TransferPlan* t = e.executor->transfer_plan()) o.planned_bytes = t->bytes_per_substep();
  std::vector<std::size_t> sizes;
  for (const auto& buffer : plan.buffers) sizes.push_back(buffer.initial.size());
  o.written_bytes = written_bytes(e.plan(), sizes);
  o.copies = e.executor->copies();
  e.executor->read_positions(o.xyz);
  return o;
}

}  // namespace

TEST_CASE("devices with memories of their own reproduce the shared-memory result bit for bit", "[memory]") {
  const std::string method =
      GENERATE(from_range(test::methods_taking([](const std::string& m) { return test::cloth_and_box_yaml(m, 12); })));
  const auto mode = GENERATE(app::ScheduleMode::split, app::ScheduleMode::heft);
  INFO(method << " " << app::to_string(mode));
  const auto scene = scene::parse_scene(test::cloth_and_box_yaml(method, 12), "s.yaml", ".");
  const plan::SubstepPlan plan = app::substep_plan_for(scene);
  const auto shared = device::DeviceSet::open("cpu/2", device::MemoryMode::shared);
  const auto separate = device::DeviceSet::open("cpu/2", device::MemoryMode::separate);
  REQUIRE(shared.memories() == 1);
  REQUIRE(separate.memories() == 2);

  const int substeps = 3;
  const Outcome a = run(shared, plan, mode, substeps);
  const Outcome b = run(separate, plan, mode, substeps);
  REQUIRE(a.xyz.size() == b.xyz.size());
  std::size_t differ = 0;
  for (std::size_t i = 0; i < a.xyz.size(); ++i) differ += a.xyz[i] != b.xyz[i] ? 1 : 0;
  CHECK(differ == 0);
  // The substeps did work: the free cloth corner fell.
  std::vector<float> start;
  for (const auto& p : plan.buffers) {
    if (p.role == plan::BufferRole::positions) start = plan::values_of<float>(p.initial);
  }
  CHECK(std::abs(b.xyz[3 * 11 + 1] - start[4 * 11 + 1]) > 1e-4);

  // One memory moves nothing; two move exactly what the transfer plan says,
  // every substep, and less than the whole state each time.
  CHECK(a.bytes == 0);
  CHECK(a.planned_bytes == 0);
  CHECK(b.planned_bytes > 0);
  CHECK(b.bytes == b.planned_bytes * substeps);
  CHECK(b.planned_bytes <= b.written_bytes);
  // The recorded substep's copies carry those bytes, each with a time.
  std::size_t recorded = 0;
  for (const auto& c : b.copies) {
    recorded += c.bytes;
    CHECK(c.ms >= 0.0);
    CHECK(std::isfinite(c.ms));
  }
  CHECK(recorded == b.planned_bytes);
}

TEST_CASE("a link between memories measures a positive latency and cost per byte", "[memory]") {
  const auto scene = scene::parse_scene(test::cloth_and_box_yaml("xpbd", 12), "s.yaml", ".");
  const auto separate = device::DeviceSet::open("cpu/2", device::MemoryMode::separate);
  app::ExecutionOptions options;
  options.mode = app::ScheduleMode::split;
  options.executor = device::ExecutorKind::events;
  options.profile_repetitions = 1;
  app::Execution e = app::prepare_execution(separate, app::substep_plan_for(scene), options);
  REQUIRE(e.executor->memories() == 2);
  const auto link = e.executor->measure_link(0, 1, 5);
  CHECK(std::isfinite(link.latency_ms));
  CHECK(link.latency_ms > 0.0);
  CHECK(std::isfinite(link.ms_per_byte));
  CHECK(link.ms_per_byte > 0.0);
  // The same devices sharing one memory have nothing to copy.
  const auto shared = device::DeviceSet::open("cpu/2", device::MemoryMode::shared);
  app::Execution s = app::prepare_execution(shared, app::substep_plan_for(scene), options);
  CHECK(s.executor->measure_link(0, 1, 5).ms_per_byte == 0.0);
}

TEST_CASE("the fused executor is refused when devices share no memory, with a clear reason", "[memory]") {
  const auto scene = scene::parse_scene(test::cloth_and_box_yaml("xpbd", 12), "s.yaml", ".");
  const auto separate = device::DeviceSet::open("cpu/2", device::MemoryMode::separate);
  app::ExecutionOptions options;
  options.mode = app::ScheduleMode::split;
  options.executor = device::ExecutorKind::fused;
  options.profile_repetitions = 1;
  CHECK_THROWS_WITH(app::prepare_execution(separate, app::substep_plan_for(scene), options), Catch::Contains("memor"));
  options.executor = device::ExecutorKind::automatic;
  app::Execution e = app::prepare_execution(separate, app::substep_plan_for(scene), options);
  CHECK(e.executor->kind() == device::ExecutorKind::events);
}

TEST_CASE("every launch of every method names what it writes, also cut into parts", "[memory][fast]") {
  // An undeclared writable argument counts as written whole: right for a
  // task that alone writes the buffer, but a part of a cut task would then
  // send the other parts' stale elements along. Every method declares.
  const std::string method =
      GENERATE(from_range(test::methods_taking([](const std::string& m) { return test::cloth_and_box_yaml(m, 12); })));
  INFO(method);
  const auto scene = scene::parse_scene(test::cloth_and_box_yaml(method, 12), "s.yaml", ".");
  const plan::SubstepPlan plan = app::cut_for_mode(app::substep_plan_for(scene), app::ScheduleMode::split, 2);
  const auto tasks = kernels::program_tasks(plan.program);
  std::size_t checked = 0;
  for (sched::TaskId t = 0; t < plan.graph.size(); ++t) {
    for (const plan::KernelLaunch& launch : plan.launches[t]) {
      const kernels::TaskSignature* sig = nullptr;
      for (const auto& s : tasks) {
        if (s.name == launch.function) sig = &s;
      }
      REQUIRE(sig != nullptr);
      for (std::size_t a = 0; a < launch.args.size() && a < sig->access.size(); ++a) {
        if (sig->access[a] != 'w') continue;
        // A part may not write a buffer whole either: the span must follow its range.
        const bool part = plan.graph.task(t).part >= 0;
        bool declared = false;
        for (const plan::WriteSpan& w : launch.writes) {
          declared =
              declared || (w.buffer == launch.args[a].buffer && !(part && w.kind == plan::WriteSpan::Kind::whole));
        }
        INFO(plan.graph.task(t).name << " " << launch.function << " argument " << a);
        CHECK(declared);
        ++checked;
      }
    }
  }
  CHECK(checked > 0);
}

TEST_CASE("asynchronous Gauss-Seidel across memories: publish and merge become copies, and the replay agrees",
          "[memory]") {
  // Every data flow of an async plan is an edge of its graph, so running
  // its schedule on device 0 alone (one memory, no copies) must give the
  // same bits as the two memories exchanging what the edges carry.
  const plan::MergeStrategy strategy =
      GENERATE(plan::MergeStrategy::average_displacements, plan::MergeStrategy::main_precedence);
  INFO(plan::to_string(strategy));
  const auto devices = device::DeviceSet::open("cpu/2", device::MemoryMode::separate);
  const auto scene = scene::parse_scene(test::cloth_and_box_yaml("xpbd", 12), "s.yaml", ".");
  const plan::SubstepPlan plan = app::substep_plan_for(scene);
  app::ExecutionOptions options;
  options.mode = app::ScheduleMode::async;
  options.executor = device::ExecutorKind::automatic;
  options.merge = strategy;
  options.profile_repetitions = 2;
  options.placement_costs = sched::CostTable(plan.graph.size(), 2, 1.0);  // placement free of timing noise
  app::Execution e = app::prepare_execution(devices, plan, options);
  REQUIRE(e.executor->kind() == device::ExecutorKind::events);
  std::vector<int> per_device(2, 0);
  for (auto d : e.assignment) ++per_device[d];
  CHECK(per_device[0] > 0);
  CHECK(per_device[1] > 0);
  CHECK(e.async_merges > 0);

  const plan::PlanState start = e.executor->read_state();
  e.executor->take_bytes_moved();
  e.executor->run_substeps(4);
  CHECK(e.executor->take_bytes_moved() == 4 * e.executor->transfer_plan()->bytes_per_substep());
  std::vector<float> executed, replayed;
  e.executor->read_positions(executed);
  app::replay_on_one_device(e);
  e.executor->reset(start);
  e.executor->run_substeps(4);
  e.executor->read_positions(replayed);
  REQUIRE(executed.size() == replayed.size());
  std::size_t differ = 0;
  for (std::size_t i = 0; i < executed.size(); ++i) differ += executed[i] != replayed[i] ? 1 : 0;
  CHECK(differ == 0);
}
