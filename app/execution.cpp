#include "app/execution.hpp"

#include <algorithm>
#include <cmath>
#include <numeric>
#include <unordered_map>

#include <fmt/format.h>

#include "plan/async_graph.hpp"
#include "plan/split_plan.hpp"
#include "scene/scene_desc.hpp"
#include "sched/cost_refit.hpp"
#include "sched/fixed_assignment.hpp"
#include "sched/gauss_seidel_rank.hpp"
#include "sched/heft.hpp"
#include "sched/sync_map.hpp"
#include "util/error.hpp"

namespace atssim::app {

namespace {

// Every pair of devices: one memory, a hop of fixed latency (an event or an
// SVM handshake); two memories, a copy of latency + bytes · ms/byte (the
// edges of the executor's plan weigh bytes).
sched::DeviceLinks measure_links(device::PlanExecutor& executor) {
  const std::size_t n = executor.device_count();
  sched::DeviceLinks links = sched::DeviceLinks::unified_memory(n, 0.0);
  for (std::size_t a = 0; a < n; ++a) {
    for (std::size_t b = 0; b < n; ++b) {
      if (a == b) continue;
      const device::PlanExecutor::Link link = executor.measure_link(a, b);
      links.set_link(static_cast<sched::DeviceId>(a), static_cast<sched::DeviceId>(b), link.latency_ms,
                     link.ms_per_byte);
    }
  }
  return links;
}

// Each device's share, inversely proportional to the time it needs for the
// whole substep alone (paper §4: balance by measured speed).
std::vector<double> speed_fractions(const sched::CostTable& costs) {
  std::vector<double> speed(costs.devices, 0.0);
  for (std::size_t d = 0; d < costs.devices; ++d) {
    double total = 0.0;
    for (std::size_t t = 0; t < costs.tasks; ++t) total += costs.at(static_cast<sched::TaskId>(t), d);
    speed[d] = 1.0 / std::max(total, 1e-9);
  }
  const double sum = std::accumulate(speed.begin(), speed.end(), 0.0);
  for (double& s : speed) s /= sum;
  return speed;
}

void make_schedule(Execution& e, const ExecutionOptions& options, bool choose_devices) {
  const auto& graph = e.plan().graph;
  if (e.mode == ScheduleMode::async && options.replay) return;  // the replay order is fixed
  if (choose_devices && e.mode == ScheduleMode::heft) {
    e.schedule = sched::schedule_heft_or_one_device(graph, e.costs.costs(), e.costs.links());
    for (sched::TaskId t = 0; t < graph.size(); ++t) e.assignment[t] = e.schedule.device_of(t);
    e.costs.plan_made();
  } else {
    e.schedule = sched::schedule_fixed(graph, e.costs.costs(), e.costs.links(), e.assignment);
  }
  e.waits = e.schedule.cross_device_waits(graph);
  e.executor->run_schedule(e.schedule, e.waits);
}

device::ExecutorOptions executor_options(const ExecutionOptions& o) {
  device::ExecutorOptions x;
  x.kind = o.executor;
  x.svm = o.svm;
  x.wait_timeout_s = o.wait_timeout_s;
  x.task_clock = o.task_clock;
  return x;
}

// Asynchronous Gauss-Seidel: HEFT with the Gauss-Seidel rank places the
// blocks of the relaxed graph (§4.1.2, §4.2.1), the sync map decides the
// merges (§4.2.2), and the merges become tasks of the plan that runs.
Execution prepare_async(const device::DeviceSet& devices, const plan::SubstepPlan& base,
                        const ExecutionOptions& options) {
  const std::size_t n = devices.size();
  Execution e;
  e.mode = ScheduleMode::async;
  const plan::SubstepPlan graph_plan = plan::async_graph(base, options.async_depth);
  const auto& graph = graph_plan.graph;

  sched::CostTable costs;
  sched::DeviceLinks hop;
  {
    device::PlanExecutor probe(devices, base, executor_options(options));
    costs = options.placement_costs ? *options.placement_costs
                                    : probe.profile(std::max(2, options.profile_repetitions / 2));
    hop = options.placement_links ? *options.placement_links : measure_links(probe);
  }
  if (costs.tasks != graph.size() || costs.devices != n) {
    throw Error(fmt::format("async: placement costs for {} tasks on {} devices, the plan has {} on {}", costs.tasks,
                            costs.devices, graph.size(), n));
  }
  // The main device keeps the stream: the fastest one runs the tasks outside
  // the iterations (predict, the velocity update), which read and write the
  // state no other device has.
  std::vector<double> total(n, 0.0);
  for (sched::TaskId t = 0; t < graph.size(); ++t) {
    for (std::size_t d = 0; d < n; ++d) total[d] += costs.at(t, d);
  }
  e.main_device = static_cast<sched::DeviceId>(std::min_element(total.begin(), total.end()) - total.begin());
  sched::TaskId predict = 0;
  for (sched::TaskId t = 0; t < graph.size(); ++t) {
    if (graph.task(t).iteration >= 0) continue;
    if (plan::kind_of(graph.task(t)) == plan::TaskKind::predict) predict = t;
    for (std::size_t d = 0; d < n; ++d) {
      if (d != e.main_device) costs.at(t, d) = sched::kCannotRun;
    }
  }
  // A hop now also publishes and merges a whole copy of the positions:
  // about two particle sweeps, priced like the predict step.
  sched::DeviceLinks links = hop;
  for (std::size_t i = 0; i < links.latency_ms.size(); ++i) {
    if (i % (n + 1) != 0) links.latency_ms[i] += 2.0 * costs.at(predict, e.main_device);
  }
  // Every Gauss-Seidel kind keeps its order across iterations (§4.1.2).
  std::vector<std::vector<sched::TaskId>> orders;
  std::vector<int> kinds;
  for (const sched::Task& t : graph.tasks()) {
    if (plan::traits(plan::kind_of(t)).gauss_seidel && std::find(kinds.begin(), kinds.end(), t.kind) == kinds.end()) {
      kinds.push_back(t.kind);
    }
  }
  for (int kind : kinds) orders.push_back(sched::gauss_seidel_order(graph, kind));
  sched::HeftOptions heft;
  heft.priority = sched::gauss_seidel_rank(graph, costs, links, orders);
  const sched::Schedule placed = sched::schedule_heft(graph, costs, links, heft);
  const sched::SyncMap map = sched::build_sync_map(graph, placed, hop, e.main_device, {options.async_latest});
  plan::AsyncPlan async = plan::make_async_plan(graph_plan, placed, map, options.merge);
  e.async_slots = async.slots;
  e.async_merges = map.merges.size();

  e.assignment = std::move(async.device);
  e.executor = std::make_unique<device::PlanExecutor>(devices, std::move(async.plan), executor_options(options));
  e.costs = sched::CostModel(e.executor->profile(options.profile_repetitions), hop, options.reschedule_drift);
  e.schedule = sched::schedule_fixed(e.plan().graph, e.costs.costs(), e.costs.links(), e.assignment);
  e.waits = e.schedule.cross_device_waits(e.plan().graph);
  e.executor->run_schedule(e.schedule, e.waits);
  if (options.replay) replay_on_one_device(e);
  return e;
}

}  // namespace

ScheduleMode parse_schedule_mode(const std::string& text) {
  if (text == "single") return ScheduleMode::single;
  if (text == "split") return ScheduleMode::split;
  if (text == "heft") return ScheduleMode::heft;
  if (text == "async") return ScheduleMode::async;
  throw input_error(fmt::format("unknown schedule '{}'; use single, split, heft or async", text));
}

std::string to_string(ScheduleMode mode) {
  switch (mode) {
    case ScheduleMode::single:
      return "single";
    case ScheduleMode::split:
      return "split";
    case ScheduleMode::heft:
      return "heft";
    case ScheduleMode::async:
      return "async";
  }
  return "?";
}

ExecutionOptions execution_options(const scene::SceneDesc& scene) {
  ExecutionOptions o;
  o.mode = parse_schedule_mode(scene.solver.schedule);
  o.executor = device::parse_executor_kind(scene.solver.executor);
  o.memory = device::parse_memory_mode(scene.memory);
  o.wait_timeout_s = scene.solver.wait_timeout_s;
  o.async_depth = scene.solver.async_depth;
  o.merge = plan::parse_merge_strategy(scene.solver.merge);
  o.async_latest = scene.solver.async_latest;
  o.replay = scene.solver.replay;
  return o;
}

void check_one_device_plan(const plan::SubstepPlan& plan, ScheduleMode mode) {
  if (mode != ScheduleMode::single && !plan.one_device_reason.empty()) {
    throw input_error(fmt::format("{}; schedule '{}' cuts or moves tasks between devices: use schedule single",
                                  plan.one_device_reason, to_string(mode)));
  }
}

Execution prepare_execution(const device::DeviceSet& devices, plan::SubstepPlan base, const ExecutionOptions& options) {
  const std::size_t n = devices.size();
  if (options.mode != ScheduleMode::single && n < 2) {
    throw input_error(
        fmt::format("schedule '{}' needs at least two devices, but the device spec selects one; "
                    "use e.g. --devices cpu/2 (the CPU split into two sub-devices)",
                    to_string(options.mode)));
  }
  check_one_device_plan(base, options.mode);
  if (options.mode == ScheduleMode::async) return prepare_async(devices, base, options);
  Execution e;
  e.mode = options.mode;
  std::vector<double> fractions(1, 1.0);
  if (options.mode == ScheduleMode::split) {
    // Measure each device's speed on the whole plan, then cut every block by it.
    device::PlanExecutor probe(devices, base, executor_options(options));
    fractions = speed_fractions(probe.profile(std::max(2, options.profile_repetitions / 2)));
  } else if (options.mode == ScheduleMode::heft) {
    fractions.assign(n, 1.0 / static_cast<double>(n));  // equal parts; HEFT places them
  }
  e.split_fractions = fractions;
  if (fractions.size() > 1) base = plan::split_plan(base, fractions);
  e.executor = std::make_unique<device::PlanExecutor>(devices, std::move(base), executor_options(options));
  sched::CostTable profiled = e.executor->profile(options.profile_repetitions);
  sched::DeviceLinks links = n > 1 ? measure_links(*e.executor) : sched::DeviceLinks::unified_memory(1, 0.0);
  e.costs = sched::CostModel(std::move(profiled), std::move(links), options.reschedule_drift);

  const auto& graph = e.plan().graph;
  e.assignment.assign(graph.size(), 0);
  if (options.mode == ScheduleMode::split) {
    for (sched::TaskId t = 0; t < graph.size(); ++t) {
      e.assignment[t] = static_cast<sched::DeviceId>(std::max(0, graph.task(t).part));
    }
    // A fused dispatcher has no work-group size to fill: cut finer.
    e.split_granule = e.executor->kind() == device::ExecutorKind::fused ? 8 : 64;
    e.part_shares = e.executor->recut(fractions, e.split_granule);
  }
  make_schedule(e, options, true);
  return e;
}

plan::SubstepPlan cut_for_mode(const plan::SubstepPlan& base, ScheduleMode mode, std::size_t devices) {
  if (mode == ScheduleMode::single || devices < 2) return base;
  const std::vector<double> equal(devices, 1.0 / static_cast<double>(devices));
  return plan::split_plan(base, equal);
}

PlannedSchedule schedule_from_costs(const plan::SubstepPlan& base, ScheduleMode mode, const sched::CostTable& costs,
                                    double latency_ms) {
  check_one_device_plan(base, mode);
  const std::size_t n = costs.devices;
  if (mode == ScheduleMode::async) {
    throw input_error("schedule 'async' needs the devices themselves (its merges are profiled); drop --costs");
  }
  if (mode != ScheduleMode::single && n < 2) {
    throw input_error(fmt::format("schedule '{}' needs costs for at least two devices", to_string(mode)));
  }
  PlannedSchedule p;
  p.plan = cut_for_mode(base, mode, n);
  p.costs = costs;
  p.links = sched::DeviceLinks::unified_memory(n, latency_ms);
  std::vector<sched::DeviceId> assignment(p.plan.graph.size(), 0);
  if (mode == ScheduleMode::split) {
    // Re-cut by speed; a part's cost scales with its share of the elements.
    p.split_fractions = speed_fractions(costs);
    const plan::SubstepPlan equal = std::move(p.plan);
    p.plan = plan::split_plan(base, p.split_fractions);
    assignment.assign(p.plan.graph.size(), 0);  // the re-cut may drop parts that rounded to nothing
    std::unordered_map<std::string, sched::TaskId> equal_id;
    for (sched::TaskId t = 0; t < equal.graph.size(); ++t) equal_id[equal.graph.task(t).name] = t;
    p.costs = sched::CostTable(p.plan.graph.size(), n);
    for (sched::TaskId t = 0; t < p.plan.graph.size(); ++t) {
      const sched::Task& task = p.plan.graph.task(t);
      assignment[t] = static_cast<sched::DeviceId>(std::max(task.part, 0));
      const auto it = equal_id.find(task.name);
      const double scale = task.part >= 0 ? p.split_fractions[task.part] * static_cast<double>(n) : 1.0;
      for (std::size_t d = 0; d < n; ++d) {
        p.costs.at(t, d) = it == equal_id.end() ? costs.at(0, d) : costs.at(it->second, d) * scale;
      }
    }
    p.schedule = sched::schedule_fixed(p.plan.graph, p.costs, p.links, assignment);
  } else if (mode == ScheduleMode::heft) {
    p.schedule = sched::schedule_heft_or_one_device(p.plan.graph, p.costs, p.links);
  } else {
    p.schedule = sched::schedule_fixed(p.plan.graph, p.costs, p.links, assignment);
  }
  p.waits = p.schedule.cross_device_waits(p.plan.graph);
  return p;
}

void replay_on_one_device(Execution& e) {
  std::vector<sched::TaskId> order(e.plan().graph.size());
  std::iota(order.begin(), order.end(), 0);
  std::stable_sort(order.begin(), order.end(), [&](sched::TaskId a, sched::TaskId b) {
    return e.schedule.slot(a).start_ms < e.schedule.slot(b).start_ms;
  });
  std::vector<std::vector<sched::Slot>> lanes(e.executor->device_count());
  double clock = 0.0;
  for (sched::TaskId t : order) {
    lanes[0].push_back({t, clock, clock + e.costs.costs().at(t, 0)});
    clock += e.costs.costs().at(t, 0);
  }
  e.assignment.assign(e.plan().graph.size(), 0);
  e.schedule = sched::assemble_schedule(e.plan().graph.size(), std::move(lanes));
  e.waits.clear();
  e.executor->run_schedule(e.schedule, e.waits);
}

FrameMeasurement measure_frame(Execution& e) {
  FrameMeasurement m;
  m.timings = e.executor->recorded();
  for (const auto& t : m.timings) m.makespan_ms = std::max(m.makespan_ms, t.finish_ms);
  if (m.timings.empty()) {
    for (const auto& l : e.executor->launches())
      m.makespan_ms = std::max(m.makespan_ms, l.ms / std::max(1, l.substeps));
  }
  return m;
}

namespace {

// Split: when the refitted costs say one device has become busier, move the
// cut (the result does not change: the blocks are exact Gauss-Seidel).
void rebalance_split(Execution& e) {
  const std::vector<double> fractions = sched::balanced_fractions(e.costs.costs(), e.assignment, e.split_fractions);
  if (fractions == e.split_fractions) return;
  const std::vector<double> shares = e.executor->recut(fractions, e.split_granule);
  std::vector<double> factor(shares.size(), 1.0);
  for (std::size_t t = 0; t < shares.size(); ++t) {
    if (e.part_shares[t] > 0.0) factor[t] = shares[t] / e.part_shares[t];
  }
  e.costs.rescale(factor);
  e.split_fractions = fractions;
  e.part_shares = shares;
}

}  // namespace

FrameMeasurement refit_and_reschedule(Execution& e, const ExecutionOptions& options) {
  FrameMeasurement m = measure_frame(e);
  m.bytes_moved = e.executor->take_bytes_moved();
  if (!m.timings.empty()) {
    e.costs.observe(m.timings, e.waits);
    e.costs.observe_copies(e.executor->copies());
  } else {
    e.costs.observe_launches(e.schedule, e.executor->launches());
  }
  if (e.mode == ScheduleMode::split) rebalance_split(e);
  make_schedule(e, options, e.mode == ScheduleMode::heft && e.costs.drifted());
  return m;
}

}  // namespace atssim::app
