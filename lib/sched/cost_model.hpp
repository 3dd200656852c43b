#pragma once
// The scheduler's cost model while a run goes on (paper §5, Table 1: costs
// re-profiled every frame with smoothing): turns what the executor measured
// into task costs and link latencies, and says when the schedule should be
// made again. Pure: timings in, tables out.
#include <span>
#include <vector>

#include "sched/cost_refit.hpp"
#include "sched/cost_table.hpp"
#include "sched/device_links.hpp"
#include "sched/schedule.hpp"
#include "sched/task_timing.hpp"

namespace atssim::sched {

// What each task of a recorded substep cost its device: from the end of the
// device's previous task to its own end, so the gap an executor leaves
// between two tasks (a launch on an in-order queue) is part of the cost, as
// pre-profiling measures it; but a task that waited for another device
// (`waits`) counts from its start, since that wait is not its cost.
// `timings` are in the order the tasks ran on each device.
std::vector<Measurement> task_costs(std::span<const TaskTiming> timings, std::size_t devices,
                                    std::span<const Wait> waits = {});

// Largest relative change of a device's total cost of the substep: single
// tasks are noisy (a few µs), a device's total is what HEFT balances.
double total_drift(const CostTable& planned, const CostTable& now);

// Largest relative change of a link's cost per byte (links priced by
// latency only are skipped): with separate memories the copies a schedule
// forces are measured only once it runs, and a link that turned out dearer
// than its probe said can make another placement (or one device) better.
double link_drift(const DeviceLinks& planned, const DeviceLinks& now);

// The hop latency an idle probe measures is a lower bound: under load a
// waiting device starts later. Every cross-device wait that held its
// consumer back (the producer finished after the consumer's device was
// free) gives one sample, the delay from the producer's end to the
// consumer's start; with 3 or more samples for a device pair, the link moves
// `weight` of the way to their median.
void refit_latency(DeviceLinks& links, std::span<const TaskTiming> timings, std::span<const Wait> waits,
                   std::size_t task_count, double weight = 0.5);

// Without per-task timings (a fused launch on a device without a task
// clock), each device's costs are scaled so that the schedule's predicted
// end on that device matches its measured launch (per substep), smoothed by
// `weight`. `predicted` is the schedule the launch ran, `assignment` the
// device of every task.
void refit_from_launches(CostTable& costs, const Schedule& predicted, std::span<const LaunchTiming> launches,
                         double weight = 0.5);

// Split schedules (every block cut between the devices by a fraction each):
// the fractions that balance the devices' measured busy time, given the
// fractions now in use. Device d does a share f_d of the cut work in the
// time its tasks cost (`assignment` gives each task's device), so its speed
// is f_d / busy_d and the new f_d is proportional to it. Returns the current
// fractions when no device is busier than another by more than `tolerance`
// (relative), so noise does not move the cut every frame.
std::vector<double> balanced_fractions(const CostTable& costs, std::span<const DeviceId> assignment,
                                       std::span<const double> fractions, double tolerance = 0.03);

// The substep's makespan a recorded frame measured: the latest task end, or
// without task timings (fused, no task clock) the longest launch per substep.
double measured_makespan_ms(std::span<const TaskTiming> timings, std::span<const LaunchTiming> launches);

class CostModel {
 public:
  CostModel() = default;
  CostModel(CostTable profiled, DeviceLinks links, double drift_threshold = 0.15);

  const CostTable& profiled() const { return profiled_; }
  const CostTable& costs() const { return costs_; }
  const DeviceLinks& links() const { return links_; }

  // One recorded substep (events, or fused with a task clock).
  void observe(std::span<const TaskTiming> timings, std::span<const Wait> waits);
  // The copies between memories of one recorded substep: each link's time
  // per byte moves halfway to what they measured.
  void observe_copies(std::span<const CopyTiming> copies);
  // One frame's launches (fused without a task clock).
  void observe_launches(const Schedule& predicted, std::span<const LaunchTiming> launches);
  // One recorded frame, whatever the executor could time: its tasks (with
  // their waits) and copies where it timed tasks, else its launches of the
  // schedule `predicted`.
  void observe_frame(std::span<const TaskTiming> timings, std::span<const Wait> waits,
                     std::span<const CopyTiming> copies, const Schedule& predicted,
                     std::span<const LaunchTiming> launches);
  // Whether the costs, or a link's cost per byte, moved by more than the
  // threshold since plan_made().
  bool drifted() const;
  // The current costs are those the schedule was just made with.
  void plan_made();
  // Multiplies every device's cost of task t by factor[t] (a task cut to
  // another share of its elements).
  void rescale(std::span<const double> factor);

 private:
  CostTable profiled_, costs_, planned_;
  DeviceLinks links_, planned_links_;
  double threshold_ = 0.15;
};

}  // namespace atssim::sched
