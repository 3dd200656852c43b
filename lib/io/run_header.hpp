#pragma once
// The header of a result file (docs/output-format.md): root attributes, the
// scene as given and resolved, /devices, /schedule's task table and /mesh,
// written once when a run creates its file; and what --resume reads back
// from it to check that it continues the same run.
#include <span>
#include <string>

#include "io/h5_handle.hpp"
#include "io/run_info.hpp"
#include "model/model.hpp"

namespace atssim::io {

constexpr int kFormatVersion = 1;

// UTC now, e.g. "2026-12-01T22:40:00Z".
std::string now_iso8601();

// Writes the header of a new result file (complete = 0, no error) and the
// empty groups the series go into.
void write_run_header(hid_t file, const RunInfo& info, std::span<const model::ObjectRange> objects);

// /scene/resolved without the keys a resumed run may change (frames, output path,
// contact.strict: what the run does when surfaces cross, not what it simulates).
std::string resumable_part(const std::string& resolved);

std::string read_string_dataset(hid_t file, const char* name);

}  // namespace atssim::io
