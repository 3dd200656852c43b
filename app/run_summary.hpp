#pragma once
// `atssim run --json`: one JSON object on stdout that says how a run went,
// so that sweep scripts need not parse text. Schema and fields:
// docs/run-json.md, docs/run-summary.schema.json.
#include <span>
#include <string>

#include "app/simulation.hpp"

namespace atssim::app {

enum class RunStatus { complete, failed, interrupted, input_error };

std::string to_string(RunStatus status);
int exit_code(RunStatus status);  // 0, 1, 1, 2 (DESIGN's exit codes)

// Nearest-rank percentile (q in [0, 1]) of `values`; NaN when empty.
double percentile(std::span<const double> values, double q);

struct RunSummaryInput {
  std::string scene_path;
  std::string command_line;
  RunStatus status = RunStatus::complete;
  std::string error;  // "" when complete
  double wall_s = 0;  // from the start of the command to its end
};

std::string run_summary_json(const RunResult& result, const RunSummaryInput& input);

}  // namespace atssim::app
