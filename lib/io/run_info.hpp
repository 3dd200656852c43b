#pragma once
// What a run records about itself in the output header (docs/output-format.md):
// the command, the scene as given and resolved, the devices, and the substep's
// tasks with what the scheduler was given. Plain data: io links no OpenCL.
#include <string>
#include <utility>
#include <vector>

#include "sched/cost_table.hpp"

namespace atssim::io {

// A device as the output describes it (plain data: the writer links no OpenCL).
struct DeviceRecord {
  std::string name, vendor, type, platform, version;
  std::string svm;  // e.g. "coarse+fine+atomics"
  int compute_units = 0;
  int index = -1;  // in `atssim devices`
  int sub_device = -1;
};

// One task of the substep plan.
struct TaskRecord {
  std::string name;
  std::string kind;  // "predict", "stretch", … (plan::TaskKind)
  int iteration = -1;
  int block = -1;
  int part = -1;
};

// The substep's tasks and what the scheduler was given.
struct ScheduleInfo {
  std::string mode;               // "single", "split", "heft", "async"
  std::string executor;           // "events" or "fused"
  std::string memory = "shared";  // "shared" (SVM within a platform) or "separate" (copies between memories)
  std::vector<TaskRecord> tasks;
  std::vector<std::pair<int, int>> edges;
  sched::CostTable costs;               // pre-profiled, ms, task × device
  std::vector<double> latency_ms;       // device × device hop latency
  std::vector<double> ms_per_byte;      // device × device copy cost per byte (separate memories; empty if shared)
  std::vector<double> split_fractions;  // share of each device ("split")
};

struct RunInfo {
  std::string command_line;
  std::string scene_yaml;     // as given
  std::string resolved_yaml;  // after defaults and --set
  std::vector<DeviceRecord> devices;
  ScheduleInfo schedule;
};

}  // namespace atssim::io
