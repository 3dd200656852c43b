#include "app/run_summary.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numeric>
#include <vector>

#include <fmt/format.h>

#include "app/json_text.hpp"

namespace atssim::app {

namespace {

constexpr int kSummaryVersion = 1;

// {"median": …, "p95": …, "mean": …, "min": …, "max": …}; nulls when empty.
std::string statistics(std::span<const double> values) {
  const double nan = std::numeric_limits<double>::quiet_NaN();
  const double mean = values.empty() ? nan : std::accumulate(values.begin(), values.end(), 0.0) / double(values.size());
  return fmt::format("{{\"median\": {}, \"p95\": {}, \"mean\": {}, \"min\": {}, \"max\": {}}}",
                     json_number(percentile(values, 0.5)), json_number(percentile(values, 0.95)), json_number(mean),
                     json_number(percentile(values, 0.0)), json_number(percentile(values, 1.0)));
}

// |measured − predicted| / measured substep makespan of every recorded frame
// that has a measurement.
std::vector<double> prediction_errors(const RunResult& r) {
  std::vector<double> errors;
  for (std::size_t i = 0; i < r.measured_makespan_ms.size() && i < r.predicted_makespan_ms.size(); ++i) {
    const double m = r.measured_makespan_ms[i], p = r.predicted_makespan_ms[i];
    if (std::isfinite(m) && std::isfinite(p) && m > 0) errors.push_back(std::abs(m - p) / m);
  }
  return errors;
}

std::string devices_json(const RunResult& r) {
  std::vector<std::string> devices;
  for (const io::DeviceRecord& d : r.devices) {
    devices.push_back(fmt::format(
        "{{\"name\": {}, \"vendor\": {}, \"type\": {}, \"compute_units\": {}, \"index\": {}, \"sub_device\": {}}}",
        json_string(d.name), json_string(d.vendor), json_string(d.type), d.compute_units, d.index, d.sub_device));
  }
  return json_array(devices);
}

std::string string_or_null(const std::string& s) { return s.empty() ? "null" : json_string(s); }

}  // namespace

std::string to_string(RunStatus status) {
  switch (status) {
    case RunStatus::complete:
      return "complete";
    case RunStatus::failed:
      return "failed";
    case RunStatus::interrupted:
      return "interrupted";
    case RunStatus::input_error:
      return "input_error";
  }
  return "failed";
}

int exit_code(RunStatus status) {
  switch (status) {
    case RunStatus::complete:
      return 0;
    case RunStatus::input_error:
      return 2;
    default:
      return 1;
  }
}

double percentile(std::span<const double> values, double q) {
  if (values.empty()) return std::numeric_limits<double>::quiet_NaN();
  std::vector<double> sorted(values.begin(), values.end());
  std::sort(sorted.begin(), sorted.end());
  const double rank = std::ceil(std::clamp(q, 0.0, 1.0) * double(sorted.size()));
  const std::size_t index = rank < 1 ? 0 : static_cast<std::size_t>(rank) - 1;
  return sorted[std::min(index, sorted.size() - 1)];
}

std::string run_summary_json(const RunResult& r, const RunSummaryInput& in) {
  const std::vector<double> errors = prediction_errors(r);
  std::string j = "{\n";
  j += fmt::format("  \"format\": \"atssim-run-summary\",\n  \"version\": {},\n", kSummaryVersion);
  j += fmt::format("  \"status\": {},\n  \"exit_code\": {},\n  \"error\": {},\n", json_string(to_string(in.status)),
                   exit_code(in.status), json_string(in.error));
  j += fmt::format("  \"scene\": {},\n  \"command_line\": {},\n", json_string(in.scene_path),
                   json_string(in.command_line));
  j += fmt::format("  \"output\": {},\n  \"xdmf\": {},\n", string_or_null(r.output_path), string_or_null(r.xdmf_path));
  j += fmt::format("  \"method\": {},\n  \"schedule\": {},\n  \"executor\": {},\n", string_or_null(r.method),
                   string_or_null(r.schedule), string_or_null(r.executor));
  j += fmt::format("  \"memory\": {},\n  \"bytes_moved_per_frame\": {},\n", string_or_null(r.memory),
                   json_number(percentile(r.bytes_moved, 0.5)));
  j += fmt::format("  \"devices\": {},\n  \"particles\": {},\n", devices_json(r), r.particles);
  j += fmt::format("  \"frames\": {{\"requested\": {}, \"simulated\": {}, \"written\": {}}},\n", r.frames_requested,
                   r.frames_simulated, r.frames_written);
  j += fmt::format("  \"ms_per_frame\": {},\n", statistics(r.frame_ms));
  j += fmt::format("  \"makespan_ms\": {{\"predicted_median\": {}, \"measured_median\": {}}},\n",
                   json_number(percentile(r.predicted_makespan_ms, 0.5)),
                   json_number(percentile(r.measured_makespan_ms, 0.5)));
  j += fmt::format("  \"prediction_error\": {{\"frames\": {}, \"median\": {}, \"p95\": {}, \"max\": {}}},\n",
                   errors.size(), json_number(percentile(errors, 0.5)), json_number(percentile(errors, 0.95)),
                   json_number(percentile(errors, 1.0)));
  j += fmt::format("  \"wall_s\": {}\n}}\n", json_number(in.wall_s));
  return j;
}

}  // namespace atssim::app
