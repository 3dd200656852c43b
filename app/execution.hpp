#pragma once
// How a substep plan runs on the chosen devices: the plan cut as the
// schedule mode needs, its executor, the costs measured on every device, and
// the schedule with its cross-device waits (DESIGN.md "Task graph of one
// substep": single, sync split, HEFT).
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "device/device_set.hpp"
#include "device/plan_executor.hpp"
#include "sched/cost_table.hpp"
#include "sched/device_links.hpp"
#include "sched/schedule.hpp"
#include "solver/async_plan.hpp"
#include "solver/substep_plan.hpp"

namespace atssim::app {

enum class ScheduleMode { single, split, heft, async };

ScheduleMode parse_schedule_mode(const std::string& text);  // throws input errors
std::string to_string(ScheduleMode mode);

struct ExecutionOptions {
  ScheduleMode mode = ScheduleMode::single;
  device::SvmMode svm = device::SvmMode::automatic;
  int profile_repetitions = 5;
  double reschedule_drift = 0.15;  // re-run HEFT when a cost moved by more than this (relative)
  // Asynchronous Gauss-Seidel (He et al. 2025 §4.2).
  int async_depth = 2;
  solver::MergeStrategy merge = solver::MergeStrategy::average_displacements;
  bool async_latest = true;
  bool replay = false;  // run the async schedule on device 0 alone, in schedule order
  // Async: costs of the base plan's tasks per device to place them with,
  // instead of a profile (tests use it to make the placement deterministic).
  std::optional<sched::CostTable> placement_costs;
};

struct Execution {
  ScheduleMode mode = ScheduleMode::single;
  std::unique_ptr<solver::SubstepPlan> plan;  // stable address: the executor refers to it
  std::unique_ptr<device::PlanExecutor> executor;
  sched::CostTable profiled;                  // pre-profiled costs (ms), task × device
  sched::CostTable costs;                     // refitted every frame
  sched::CostTable planned;                   // the costs the current assignment was chosen with
  sched::DeviceLinks links;                   // measured event-hop latency per device pair
  std::vector<sched::DeviceId> assignment;    // device per task
  sched::Schedule schedule;                   // predicted times under `costs`
  std::vector<sched::Wait> waits;
  std::vector<double> split_fractions;        // split mode: share of each device
  sched::DeviceId main_device = 0;            // async: the device that keeps the stream
  int async_slots = 0;                        // async: snapshot buffers
  std::size_t async_merges = 0;               // async: merges per substep
};

// Builds, profiles and schedules. Throws atssim::Error (input) when the mode
// needs more devices than the set has.
Execution prepare_execution(const device::DeviceSet& devices, const solver::SubstepPlan& base,
                            const ExecutionOptions& options);

// The schedule from a given cost table instead of a profile (`atssim
// schedule --costs`): `costs` belongs to the plan cut for `mode` into equal
// parts, one per device (uncut for single). For split, the parts are then
// re-cut by the devices' speeds in `costs` and each part's cost scaled by
// its share. No device is touched.
struct PlannedSchedule {
  solver::SubstepPlan plan;
  sched::CostTable costs;
  sched::DeviceLinks links;
  sched::Schedule schedule;
  std::vector<sched::Wait> waits;
  std::vector<double> split_fractions;
};
solver::SubstepPlan cut_for_mode(const solver::SubstepPlan& base, ScheduleMode mode, std::size_t devices);
PlannedSchedule schedule_from_costs(const solver::SubstepPlan& base, ScheduleMode mode, const sched::CostTable& costs,
                                    double latency_ms);

// Replay (async): runs the current schedule's tasks on device 0 alone, in
// the order of their predicted starts. Every data flow of an async plan is
// an edge of its graph, so this reproduces the executed result exactly.
void replay_on_one_device(Execution& execution);

// After a recorded substep: refits the costs from its timings (smoothing,
// sched::refit_costs), recomputes the predicted times, and for `heft`
// re-runs HEFT when the costs drifted. Returns the measured timings.
std::vector<device::TaskTiming> refit_and_reschedule(Execution& execution, const ExecutionOptions& options);

}  // namespace atssim::app
