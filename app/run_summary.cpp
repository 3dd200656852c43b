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

std::string surface_frame_json(const RunResult::ContactRecord& c) {
  return fmt::format(
      "{{\"frame\": {}, \"surface_pairs\": {}, \"surface_max_penetration\": {}, \"surface_crossings\": {}}}", c.frame,
      c.values.surface_pairs, json_number(c.values.surface_max_penetration), c.values.surface_crossings);
}

// Whether a's surfaces are in a worse state than b's: more crossings, then
// a deeper penetration, then more pairs.
bool worse(const io::ContactFrame& a, const io::ContactFrame& b) {
  if (a.surface_crossings != b.surface_crossings) return a.surface_crossings > b.surface_crossings;
  if (a.surface_max_penetration != b.surface_max_penetration)
    return a.surface_max_penetration > b.surface_max_penetration;
  return a.surface_pairs > b.surface_pairs;
}

// The surfaces over the written frames (null without a contact surface).
std::string contact_json(const RunResult& r) {
  if (!r.surface_contact) return "null";
  const RunResult::ContactRecord* worst = nullptr;
  const RunResult::ContactRecord* first_crossing = nullptr;
  int crossed = 0;
  for (const RunResult::ContactRecord& c : r.contact) {
    if (worst == nullptr || worse(c.values, worst->values)) worst = &c;
    if (c.values.surface_crossings > 0) {
      ++crossed;
      if (first_crossing == nullptr) first_crossing = &c;
    }
  }
  return fmt::format("{{\"frames\": {}, \"crossed_frames\": {}, \"first_crossing\": {}, \"last\": {}, \"worst\": {}}}",
                     r.contact.size(), crossed, first_crossing ? std::to_string(first_crossing->frame) : "null",
                     r.contact.empty() ? "null" : surface_frame_json(r.contact.back()),
                     worst ? surface_frame_json(*worst) : "null");
}

std::string decision_json(const io::DecisionRecord& d) {
  return fmt::format(
      "{{\"frame\": {}, \"method\": {}, \"iterations\": {}, \"schedule\": {}, \"y\": {}, \"previous_y\": {}, "
      "\"y_floor\": {}, \"predicted_ms\": {}, \"measured_ms\": {}, \"check_ms\": {}, \"changed\": {}, "
      "\"reason\": {}}}",
      d.frame, json_string(d.method), d.iterations, json_string(d.schedule), json_number(d.y),
      json_number(d.previous_y), json_number(d.y_floor), json_number(d.predicted_ms), json_number(d.measured_ms),
      json_number(d.check_ms), d.changed != 0 ? "true" : "false", json_string(d.reason));
}

// What --tolerance / --budget asked and chose (null without either).
std::string accuracy_json(const RunResult& r) {
  if (!r.tuned) return "null";
  std::vector<std::string> rows;
  for (const io::DecisionRecord& d : r.decisions) rows.push_back(decision_json(d));
  std::string list = "[]";
  if (!rows.empty()) {
    list = "[\n";
    for (std::size_t i = 0; i < rows.size(); ++i) list += "    " + rows[i] + (i + 1 < rows.size() ? ",\n" : "\n");
    list += "  ]";
  }
  return fmt::format("{{\"tolerance\": {}, \"budget_ms\": {}, \"recheck\": {}, \"decisions\": {}}}",
                     r.tolerance > 0.0 ? json_number(r.tolerance) : "null",
                     r.budget_ms > 0.0 ? json_number(r.budget_ms) : "null", r.recheck, list);
}

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
  j += fmt::format("  \"host_ms_per_frame\": {},\n", statistics(r.host_ms));
  j += fmt::format("  \"makespan_ms\": {{\"predicted_median\": {}, \"measured_median\": {}}},\n",
                   json_number(percentile(r.predicted_makespan_ms, 0.5)),
                   json_number(percentile(r.measured_makespan_ms, 0.5)));
  j += fmt::format("  \"prediction_error\": {{\"frames\": {}, \"median\": {}, \"p95\": {}, \"max\": {}}},\n",
                   errors.size(), json_number(percentile(errors, 0.5)), json_number(percentile(errors, 0.95)),
                   json_number(percentile(errors, 1.0)));
  j += fmt::format("  \"contact\": {},\n", contact_json(r));
  j += fmt::format("  \"accuracy\": {},\n", accuracy_json(r));
  j += fmt::format("  \"wall_s\": {}\n}}\n", json_number(in.wall_s));
  return j;
}

}  // namespace atssim::app
