#pragma once
// Cost tables as CSV, for `atssim schedule --costs FILE`:
//   # comment lines and blank lines are ignored
//   latency_ms,0.015            optional: the cross-device hop (every pair)
//   task,dev0_ms,dev1_ms        optional header
//   predict,0.021,0.020         one line per task: its name, then ms per device
#include <string>
#include <vector>

#include "sched/cost_table.hpp"
#include "sched/task_graph.hpp"

namespace atssim::io {

struct CostFile {
  sched::CostTable costs;  // rows in the graph's task order
  double latency_ms = 0.0;
};

// Reads `path` and orders its rows by the tasks of `graph`. Throws
// atssim::Error (input) naming the file and line for a malformed line, a
// task the graph lacks, a task the file lacks, or rows of unequal length.
CostFile read_cost_file(const std::string& path, const sched::TaskGraph& graph);

// The number of devices (cost columns) of the file's first task line.
std::size_t cost_file_devices(const std::string& path);

// The same format, for a table measured by atssim.
std::string format_cost_file(const sched::TaskGraph& graph, const sched::CostTable& costs, double latency_ms);

}  // namespace atssim::io
