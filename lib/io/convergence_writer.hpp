#pragma once
// `atssim converge` results as HDF5 (/convergence, docs/output-format.md).
#include <string>
#include <vector>

namespace atssim::io {

struct ConvergenceTrace {
  std::string variant;                 // e.g. "xpbd/async/average_displacements"
  std::vector<int> iterations;         // k
  std::vector<double> energy;          // E_k
  std::vector<double> relative_error;  // y_k = (E_k - E*) / (E_0 - E*)
  std::vector<double> time_ms;         // measured substep makespan with k iterations
};

struct ConvergenceResult {
  std::string command_line;
  std::string scene_yaml, resolved_yaml;
  int frames_before = 0;
  std::string from;  // --from: the result file whose last checkpoint was the state ("" = frames_before)
  double substep_dt = 0.0;
  double energy_start = 0.0;      // E_0 = E(x~)
  double energy_reference = 0.0;  // E* (Newton)
  int newton_iterations = 0;
  double newton_relative_gradient = 0.0;
  std::string newton_status;
  // (E(x* in float32) − E*) / (E_0 − E*): the y no float32 method gets
  // below on this state (NaN when E_0 ≤ E*).
  double y_floor = 0.0;
  std::vector<ConvergenceTrace> traces;
};

// Writes (truncates) `path`; throws atssim::Error when it cannot.
void write_convergence(const std::string& path, const ConvergenceResult& result);

}  // namespace atssim::io
