#pragma once
// How a substep plan runs on the chosen devices: the plan cut as the
// schedule mode needs, its executor, the costs measured on every device, and
// the schedule with its cross-device waits (DESIGN.md "Task graph of one
// substep": single, sync split, HEFT, async).
#include <limits>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "device/device_set.hpp"
#include "device/plan_executor.hpp"
#include "plan/async_plan.hpp"
#include "plan/substep_plan.hpp"
#include "sched/cost_model.hpp"
#include "sched/cost_table.hpp"
#include "sched/device_links.hpp"
#include "sched/schedule.hpp"

namespace atssim::scene {
struct SceneDesc;
}

namespace atssim::app {

enum class ScheduleMode { single, split, heft, async };

ScheduleMode parse_schedule_mode(const std::string& text);  // throws input errors
// Throws an input error when `plan` is for one device only
// (SubstepPlan::one_device_reason) and `mode` is not single.
void check_one_device_plan(const plan::SubstepPlan& plan, ScheduleMode mode);
std::string to_string(ScheduleMode mode);

struct ExecutionOptions {
  ScheduleMode mode = ScheduleMode::single;
  device::ExecutorKind executor = device::ExecutorKind::automatic;
  device::MemoryMode memory = device::MemoryMode::shared;  // which DeviceSet to open (devices of the scene)
  device::SvmMode svm = device::SvmMode::automatic;
  double wait_timeout_s = 10.0;  // fused: a run without progress this long fails
  bool task_clock = true;        // fused: time tasks by the device cycle counter (false: whole launches only)
  int profile_repetitions = 5;
  double reschedule_drift = 0.15;  // re-run HEFT when a device's total cost moved by more than this (relative)
  // Asynchronous Gauss-Seidel (He et al. 2025 §4.2).
  int async_depth = 2;
  plan::MergeStrategy merge = plan::MergeStrategy::average_displacements;
  bool async_latest = true;
  bool replay = false;  // run the async schedule on device 0 alone, in schedule order
  // heft: colour blocks merged where HEFT then predicts a shorter substep
  // (sched::schedule_heft_merging; solver.task_merging).
  bool task_merging = true;
  // Async: costs of the base plan's tasks per device to place them with,
  // instead of a profile, and the links between the devices instead of a
  // measured hop; heft: the same for the first schedule, of the tasks of
  // cut_for_mode(plan, heft, devices) (later frames refit from measured
  // times). Tests use both to make the placement deterministic.
  std::optional<sched::CostTable> placement_costs;
  std::optional<sched::DeviceLinks> placement_links;
};

// The options a scene asks for (solver.schedule, solver.executor, the async
// keys): the one mapping that `run`, `schedule` and `converge` share.
ExecutionOptions execution_options(const scene::SceneDesc& scene);

struct Execution {
  ScheduleMode mode = ScheduleMode::single;
  std::unique_ptr<device::PlanExecutor> executor;  // owns the plan it runs
  sched::CostModel costs;                          // profiled, then refitted every frame
  std::vector<sched::DeviceId> assignment;         // device per task
  sched::Schedule schedule;                        // predicted times under the current costs
  std::vector<sched::Wait> waits;
  std::vector<double> split_fractions;  // split mode: share of each device
  std::vector<double> part_shares;      // split mode: each task's share of its whole task
  std::size_t split_granule = 64;       // split mode: parts end on multiples of this
  sched::DeviceId main_device = 0;      // async: the device that keeps the stream
  int async_slots = 0;                  // async: snapshot buffers
  std::size_t async_merges = 0;         // async: merges per substep
  // heft: the merge HEFT last chose (blocks per group, 0: none), each task's
  // merged task (-1: alone) and the makespan predicted without merging.
  std::size_t merge_blocks = 0;
  std::vector<int> merge_group;
  double unmerged_makespan_ms = std::numeric_limits<double>::quiet_NaN();

  const plan::SubstepPlan& plan() const { return executor->plan(); }
};

// Pre-profiling: the executor runs `repetitions` substeps after the warm-up
// and reports each task's time; sched::ProfileCosts prices them.
sched::CostTable profile(device::PlanExecutor& executor, int repetitions);

// Builds, profiles and schedules (the executor ends up owning the plan, so
// pass it moved when it is not needed afterwards). Throws atssim::Error
// (input) when the mode needs more devices than the set has.
Execution prepare_execution(const device::DeviceSet& devices, plan::SubstepPlan base, const ExecutionOptions& options);

// The schedule from a given cost table instead of a profile (`atssim
// schedule --costs`): `costs` belongs to the plan cut for `mode` into equal
// parts, one per device (uncut for single). For split, the parts are then
// re-cut by the devices' speeds in `costs` and each part's cost scaled by
// its share. No device is touched. heft merges colour blocks as a run does
// (ExecutionOptions::task_merging) unless `task_merging` is false.
struct PlannedSchedule {
  plan::SubstepPlan plan;
  sched::CostTable costs;
  sched::DeviceLinks links;
  sched::Schedule schedule;
  std::vector<sched::Wait> waits;
  std::vector<double> split_fractions;
  std::vector<int> merge_group;  // heft: each task's merged task, -1 alone (empty: none)
  double unmerged_makespan_ms = std::numeric_limits<double>::quiet_NaN();  // heft: HEFT without merging
};
plan::SubstepPlan cut_for_mode(const plan::SubstepPlan& base, ScheduleMode mode, std::size_t devices);
PlannedSchedule schedule_from_costs(const plan::SubstepPlan& base, ScheduleMode mode, const sched::CostTable& costs,
                                    double latency_ms, bool task_merging = true);

// Replay (async): runs the current schedule's tasks on device 0 alone, in
// the order of their predicted starts. Every data flow of an async plan is
// an edge of its graph, so this reproduces the executed result exactly.
void replay_on_one_device(Execution& execution);

// What a recorded frame measured: its tasks (empty for fused execution
// without a task clock) and the substep makespan.
struct FrameMeasurement {
  std::vector<sched::TaskTiming> timings;
  double makespan_ms = 0.0;
  std::size_t bytes_moved = 0;  // copied between memories by the frame (devices that share none)
};

// What the last recorded run_substeps() measured.
FrameMeasurement measure_frame(Execution& execution);

// After a recorded frame: refits the costs from what it measured (the cost
// model), recomputes the predicted times, for `heft` re-runs HEFT when the
// costs drifted, and for `split` moves the cut when one device has become
// busier than the other (sched::balanced_fractions).
FrameMeasurement refit_and_reschedule(Execution& execution, const ExecutionOptions& options);

}  // namespace atssim::app
