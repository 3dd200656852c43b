#include "app/execution.hpp"

#include <algorithm>
#include <stdexcept>

#include <fmt/format.h>

#include "plan/async_graph.hpp"
#include "plan/async_placement.hpp"
#include "plan/split_plan.hpp"
#include "scene/scene_desc.hpp"
#include "sched/fixed_assignment.hpp"
#include "sched/heft.hpp"
#include "sched/merged_heft.hpp"
#include "sched/profile_costs.hpp"
#include "sched/split_shares.hpp"
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

// The merges HEFT tries (sched/merged_heft.hpp): the parts of each block,
// and 2, 4 or 8 consecutive blocks.
constexpr std::size_t kMergeSizes[] = {1, 2, 4, 8};

void make_schedule(Execution& e, const ExecutionOptions& options, bool choose_devices) {
  const auto& graph = e.plan().graph;
  if (e.mode == ScheduleMode::async && options.replay) return;  // the replay order is fixed
  if (choose_devices && e.mode == ScheduleMode::heft) {
    if (options.task_merging) {
      sched::MergedHeft m = sched::schedule_heft_merging(graph, e.costs.costs(), e.costs.links(), kMergeSizes);
      e.schedule = std::move(m.schedule);
      e.merge_blocks = m.blocks_per_group;
      e.merge_group = std::move(m.group);
      e.unmerged_makespan_ms = m.unmerged_makespan_ms;
    } else {
      e.schedule = sched::schedule_heft_or_one_device(graph, e.costs.costs(), e.costs.links());
      e.unmerged_makespan_ms = e.schedule.makespan_ms;
    }
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

// Asynchronous Gauss-Seidel: the relaxed graph placed (plan::place_async),
// its merges made tasks of the plan that runs (plan::make_async_plan).
Execution prepare_async(const device::DeviceSet& devices, const plan::SubstepPlan& base,
                        const ExecutionOptions& options) {
  Execution e;
  e.mode = ScheduleMode::async;
  const plan::SubstepPlan graph_plan = plan::async_graph(base, options.async_depth);
  sched::CostTable costs;
  sched::DeviceLinks hop;
  {
    device::PlanExecutor probe(devices, base, executor_options(options));
    costs = options.placement_costs ? *options.placement_costs
                                    : profile(probe, std::max(2, options.profile_repetitions / 2));
    hop = options.placement_links ? *options.placement_links : measure_links(probe);
  }
  const plan::AsyncPlacement placement = plan::place_async(graph_plan, std::move(costs), hop, options.async_latest);
  plan::AsyncPlan async = plan::make_async_plan(graph_plan, placement.placed, placement.map, options.merge);
  e.main_device = placement.main_device;
  e.async_slots = async.slots;
  e.async_merges = placement.map.merges.size();

  e.assignment = std::move(async.device);
  e.executor = std::make_unique<device::PlanExecutor>(devices, std::move(async.plan), executor_options(options));
  e.costs = sched::CostModel(profile(*e.executor, options.profile_repetitions), hop, options.reschedule_drift);
  e.schedule = sched::schedule_fixed(e.plan().graph, e.costs.costs(), e.costs.links(), e.assignment);
  e.waits = e.schedule.cross_device_waits(e.plan().graph);
  e.executor->run_schedule(e.schedule, e.waits);
  if (options.replay) replay_on_one_device(e);
  return e;
}

}  // namespace

sched::CostTable profile(device::PlanExecutor& executor, int repetitions) {
  const sched::ProfileOptions options;
  sched::ProfileCosts costs(executor.plan().graph.size(), executor.device_count(), options);
  executor.profile(options.warmup + repetitions, costs, options.warmup + std::min(options.min_timed, repetitions),
                   options.budget_ms);
  return costs.costs();
}

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
  o.task_merging = scene.solver.task_merging;
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
    fractions = sched::speed_fractions(profile(probe, std::max(2, options.profile_repetitions / 2)));
  } else if (options.mode == ScheduleMode::heft) {
    fractions = sched::equal_fractions(n);  // HEFT places the parts
  }
  e.split_fractions = fractions;
  if (fractions.size() > 1) base = plan::split_plan(base, fractions);
  e.executor = std::make_unique<device::PlanExecutor>(devices, std::move(base), executor_options(options));
  const bool heft = options.mode == ScheduleMode::heft;
  const bool placed = heft && options.placement_costs;
  if (placed && (options.placement_costs->tasks != e.plan().graph.size() || options.placement_costs->devices != n)) {
    throw std::logic_error(fmt::format("placement costs for {} tasks on {} devices; the heft plan has {} on {}",
                                       options.placement_costs->tasks, options.placement_costs->devices,
                                       e.plan().graph.size(), n));
  }
  sched::CostTable profiled = placed ? *options.placement_costs : profile(*e.executor, options.profile_repetitions);
  sched::DeviceLinks links = sched::DeviceLinks::unified_memory(1, 0.0);
  if (heft && options.placement_links) {
    links = *options.placement_links;
  } else if (n > 1) {
    links = measure_links(*e.executor);
  }
  e.costs = sched::CostModel(std::move(profiled), std::move(links), options.reschedule_drift);

  e.assignment.assign(e.plan().graph.size(), 0);
  if (options.mode == ScheduleMode::split) {
    e.assignment = sched::part_devices(e.plan().graph);
    e.split_granule = plan::part_granule(e.executor->work_group_elements());
    e.part_shares = e.executor->recut(fractions, e.split_granule);
  }
  make_schedule(e, options, true);
  return e;
}

plan::SubstepPlan cut_for_mode(const plan::SubstepPlan& base, ScheduleMode mode, std::size_t devices) {
  if (mode == ScheduleMode::single || devices < 2) return base;
  return plan::split_plan(base, sched::equal_fractions(devices));
}

PlannedSchedule schedule_from_costs(const plan::SubstepPlan& base, ScheduleMode mode, const sched::CostTable& costs,
                                    double latency_ms, bool task_merging) {
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
  if (mode == ScheduleMode::split) {
    // Re-cut by speed (every part kept: the task ids stay those of the equal
    // cut the costs are for); a part's cost scales with its share.
    p.split_fractions = sched::speed_fractions(costs);
    p.plan = plan::split_plan(base, p.split_fractions);
    p.costs = sched::costs_for_fractions(p.plan.graph, costs, p.split_fractions);
    p.schedule = sched::schedule_fixed(p.plan.graph, p.costs, p.links, sched::part_devices(p.plan.graph));
  } else if (mode == ScheduleMode::heft) {
    if (task_merging) {
      sched::MergedHeft m = sched::schedule_heft_merging(p.plan.graph, p.costs, p.links, kMergeSizes);
      p.schedule = std::move(m.schedule);
      p.merge_group = std::move(m.group);
      p.unmerged_makespan_ms = m.unmerged_makespan_ms;
    } else {
      p.schedule = sched::schedule_heft_or_one_device(p.plan.graph, p.costs, p.links);
      p.unmerged_makespan_ms = p.schedule.makespan_ms;
    }
  } else {
    p.schedule =
        sched::schedule_fixed(p.plan.graph, p.costs, p.links, std::vector<sched::DeviceId>(p.plan.graph.size(), 0));
  }
  p.waits = p.schedule.cross_device_waits(p.plan.graph);
  return p;
}

void replay_on_one_device(Execution& e) {
  e.schedule = sched::replay_on_device0(e.schedule, e.costs.costs(), e.executor->device_count());
  e.assignment.assign(e.plan().graph.size(), 0);
  e.waits.clear();
  e.executor->run_schedule(e.schedule, e.waits);
}

FrameMeasurement measure_frame(Execution& e) {
  FrameMeasurement m;
  m.timings = e.executor->recorded();
  m.makespan_ms = sched::measured_makespan_ms(m.timings, e.executor->launches());
  return m;
}

namespace {

// Split: when the refitted costs say one device has become busier, move the
// cut (the result does not change: the blocks are exact Gauss-Seidel).
void rebalance_split(Execution& e) {
  const std::vector<double> fractions = sched::balanced_fractions(e.costs.costs(), e.assignment, e.split_fractions);
  if (fractions == e.split_fractions) return;
  const std::vector<double> shares = e.executor->recut(fractions, e.split_granule);
  e.costs.rescale(sched::share_factors(e.part_shares, shares));
  e.split_fractions = fractions;
  e.part_shares = shares;
}

}  // namespace

FrameMeasurement refit_and_reschedule(Execution& e, const ExecutionOptions& options) {
  FrameMeasurement m = measure_frame(e);
  m.bytes_moved = e.executor->take_bytes_moved();
  e.costs.observe_frame(m.timings, e.waits, e.executor->copies(), e.schedule, e.executor->launches());
  if (e.mode == ScheduleMode::split) rebalance_split(e);
  make_schedule(e, options, e.mode == ScheduleMode::heft && e.costs.drifted());
  return m;
}

}  // namespace atssim::app
