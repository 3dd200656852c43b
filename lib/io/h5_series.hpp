#pragma once
// Extendible datasets chunked by frame: the per-frame series of the output
// (frames, timing, schedule, contact), appended row by row and cut back to a
// checkpoint on --resume.
#include <span>
#include <string>

#include "io/h5_handle.hpp"

namespace atssim::io {

// An extendible 1-D (cols = 0) or [F, rows, cols] dataset, chunked by frame.
H5Handle create_series(hid_t parent, const std::string& name, std::size_t rows, std::size_t cols, hid_t file_type);

// The length of a series' first dimension.
hsize_t rows_of(hid_t set);

// Cuts a series back to `rows` along its first dimension (no-op when it has them).
void truncate_rows(hid_t set, hsize_t rows);

// Appends `values` to a 1-D series that holds `rows` rows.
void append_series_rows(hid_t set, const void* values, std::size_t count, hid_t mem_type, hsize_t rows);

template <typename T>
void append_series_rows(hid_t set, std::span<const T> values, hid_t mem_type, hsize_t rows) {
  append_series_rows(set, values.data(), values.size(), mem_type, rows);
}

}  // namespace atssim::io
