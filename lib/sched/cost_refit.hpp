#pragma once
// Keeping the cost table honest while the simulation runs (paper §5 / Table 1:
// "costs re-profiled every frame with smoothing"; DESIGN.md "Costs come from
// pre-profiling … then every frame from OpenCL profiling events, smoothed").
//
// Smoothing rule (exponential moving average, as the paper's public code
// does with weight ½): after each measurement m of a task on a device,
//   cost ← cost + weight · (m − cost).
// Weight 1 trusts the last measurement alone; small weights damp noise.
// Re-schedule when cost_drift() between the table a schedule was made with
// and the refitted one exceeds a threshold; schedule onto devices still busy
// with earlier work through ListOptions::device_ready_ms.
#include <span>
#include <vector>

#include "sched/cost_table.hpp"

namespace atssim::sched {

struct Measurement {
  TaskId task = 0;
  DeviceId device = 0;
  double ms = 0.0;
};

struct RefitOptions {
  double weight = 0.5;  // in (0, 1]
};

// Applies the measurements in order. Throws atssim::Error for a measurement
// of a task or device outside the table, a negative or non-finite time, or
// a device the table says cannot run the task.
void refit_costs(CostTable& costs, std::span<const Measurement> measurements, const RefitOptions& options = {});

// Largest relative change |now − planned| / planned over the finite entries
// (an entry going from 0 to non-zero counts as 1). Tables of different shape
// or differing in which entries are inf: +inf.
double cost_drift(const CostTable& planned, const CostTable& now);

// Pre-profiling: mean of the samples after dropping the `trim` fraction at
// each end (trim 0.1 drops the lowest and highest 10 %). Robust to the first
// launch's compile/warm-up time and to stray preemptions.
double trimmed_mean(std::vector<double> samples, double trim = 0.1);

}  // namespace atssim::sched
