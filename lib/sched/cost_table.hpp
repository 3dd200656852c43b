#pragma once
// Computation cost of every task on every device, in milliseconds
// (paper §3.3.1: "computation matrices"). `kCannotRun` (+inf) marks a device
// that cannot run the task; a scheduler never places a task there.
#include <cstddef>
#include <limits>
#include <span>
#include <vector>

#include "sched/ids.hpp"

namespace atssim::sched {

inline constexpr double kCannotRun = std::numeric_limits<double>::infinity();

struct CostTable {
  std::size_t tasks = 0;
  std::size_t devices = 0;
  std::vector<double> ms;  // row-major: ms[task * devices + device]

  CostTable() = default;
  CostTable(std::size_t tasks, std::size_t devices, double fill = kCannotRun);
  // One row per task, one column per device; every row must be as long.
  static CostTable from_rows(const std::vector<std::vector<double>>& rows);

  double& at(TaskId task, DeviceId device) { return ms[task * devices + device]; }
  double at(TaskId task, DeviceId device) const { return ms[task * devices + device]; }
  std::span<const double> row(TaskId task) const { return {ms.data() + task * devices, devices}; }
  bool can_run(TaskId task, DeviceId device) const { return at(task, device) < kCannotRun; }

  // Adds a device column filled with `fill` (e.g. a device nothing can use).
  void add_device(double fill = kCannotRun);
};

// Mean cost of `task` over the devices that can run it (HEFT's w̄, paper
// §3.3.2). Averaging only finite entries keeps a device that cannot run the
// task from changing its rank. +inf when no device can run it.
double mean_cost(const CostTable& costs, TaskId task);

// Smallest cost of `task` over all devices (+inf when none can run it).
double min_cost(const CostTable& costs, TaskId task);

}  // namespace atssim::sched
