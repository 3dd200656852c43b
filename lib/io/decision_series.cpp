#include "io/decision_series.hpp"

#include <algorithm>
#include <cstring>

#include "io/h5_series.hpp"

namespace atssim::io {

namespace {

constexpr std::size_t kNameBytes = 16;     // method and schedule names
constexpr std::size_t kReasonBytes = 160;  // one line; longer reasons are cut

// A fixed-length string type (h5py reads it as bytes: .astype(str)).
H5Handle string_type(std::size_t bytes) {
  H5Handle t = h5_check(H5Tcopy(H5T_C_S1), H5Tclose, "string type");
  h5_check(H5Tset_size(t, bytes), "string size");
  h5_check(H5Tset_strpad(t, H5T_STR_NULLPAD), "string padding");
  return t;
}

H5Handle open_set(hid_t group, const char* name) {
  return h5_check(H5Dopen2(group, name, H5P_DEFAULT), H5Dclose, std::string("opening /decisions/") + name);
}

// Writes one value at `row` of a 1-D series that already has that row.
void write_at(hid_t set, std::size_t row, const void* value, hid_t mem_type) {
  H5Handle space = h5_check(H5Dget_space(set), H5Sclose, "series space");
  const hsize_t start[1] = {row}, one[1] = {1};
  h5_check(H5Sselect_hyperslab(space, H5S_SELECT_SET, start, nullptr, one, nullptr), "selecting a row");
  H5Handle mem = h5_check(H5Screate_simple(1, one, nullptr), H5Sclose, "memory space");
  h5_check(H5Dwrite(set, mem_type, mem, space, H5P_DEFAULT, value), "writing a row of /decisions");
}

template <typename T>
std::vector<T> read_all(hid_t set, hid_t mem_type, std::size_t rows) {
  std::vector<T> v(rows);
  if (rows > 0) h5_check(H5Dread(set, mem_type, H5S_ALL, H5S_ALL, H5P_DEFAULT, v.data()), "reading /decisions");
  return v;
}

std::vector<std::string> read_strings(hid_t set, std::size_t bytes, std::size_t rows) {
  H5Handle type = string_type(bytes);
  std::vector<char> raw(rows * bytes);
  if (rows > 0) h5_check(H5Dread(set, type, H5S_ALL, H5S_ALL, H5P_DEFAULT, raw.data()), "reading /decisions");
  std::vector<std::string> out;
  for (std::size_t r = 0; r < rows; ++r) {
    const char* s = raw.data() + r * bytes;
    out.emplace_back(s, strnlen(s, bytes));
  }
  return out;
}

}  // namespace

const DecisionSeries::Column DecisionSeries::kColumns[] = {
    {"frame", &DecisionSeries::frame_},
    {"method", &DecisionSeries::method_},
    {"iterations", &DecisionSeries::iterations_},
    {"schedule", &DecisionSeries::schedule_},
    {"y", &DecisionSeries::y_},
    {"previous_y", &DecisionSeries::previous_y_},
    {"y_floor", &DecisionSeries::y_floor_},
    {"predicted_ms", &DecisionSeries::predicted_},
    {"measured_ms", &DecisionSeries::measured_},
    {"check_ms", &DecisionSeries::check_},
    {"changed", &DecisionSeries::changed_},
    {"reason", &DecisionSeries::reason_},
};

DecisionSeries DecisionSeries::create(hid_t file) {
  DecisionSeries s;
  H5Handle g = create_group(file, "decisions");
  H5Handle names = string_type(kNameBytes), reasons = string_type(kReasonBytes);
  s.frame_ = create_series(g, "frame", 0, 0, H5T_STD_I32LE);
  s.method_ = create_series(g, "method", 0, 0, names);
  s.iterations_ = create_series(g, "iterations", 0, 0, H5T_STD_I32LE);
  s.schedule_ = create_series(g, "schedule", 0, 0, names);
  s.y_ = create_series(g, "y", 0, 0, H5T_IEEE_F64LE);
  s.previous_y_ = create_series(g, "previous_y", 0, 0, H5T_IEEE_F64LE);
  s.y_floor_ = create_series(g, "y_floor", 0, 0, H5T_IEEE_F64LE);
  s.predicted_ = create_series(g, "predicted_ms", 0, 0, H5T_IEEE_F64LE);
  s.measured_ = create_series(g, "measured_ms", 0, 0, H5T_IEEE_F64LE);
  s.check_ = create_series(g, "check_ms", 0, 0, H5T_IEEE_F64LE);
  s.changed_ = create_series(g, "changed", 0, 0, H5T_STD_I32LE);
  s.reason_ = create_series(g, "reason", 0, 0, reasons);
  return s;
}

DecisionSeries DecisionSeries::open(hid_t file, long long keep_through) {
  std::vector<DecisionRecord> kept = read_decisions(file);
  if (H5Lexists(file, "decisions", H5P_DEFAULT) <= 0) return create(file);
  H5Handle g = h5_check(H5Gopen2(file, "decisions", H5P_DEFAULT), H5Gclose, "opening /decisions");
  DecisionSeries s;
  for (const Column& c : kColumns) s.*c.member = open_set(g, c.name);
  const auto past = std::find_if(kept.begin(), kept.end(), [&](const auto& r) { return r.frame > keep_through; });
  kept.erase(past, kept.end());
  for (const Column& c : kColumns) truncate_rows(s.*c.member, kept.size());
  s.rows_ = std::move(kept);
  return s;
}

void DecisionSeries::write_row(std::size_t index, bool extend) {
  const DecisionRecord& r = rows_[index];
  if (extend) {
    const hsize_t size[1] = {index + 1};
    for (const Column& c : kColumns) h5_check(H5Dset_extent(this->*c.member, size), "extending /decisions");
  }
  H5Handle names = string_type(kNameBytes), reasons = string_type(kReasonBytes);
  char method[kNameBytes] = {}, schedule[kNameBytes] = {}, reason[kReasonBytes] = {};
  std::memcpy(method, r.method.data(), std::min(r.method.size(), kNameBytes));
  std::memcpy(schedule, r.schedule.data(), std::min(r.schedule.size(), kNameBytes));
  std::memcpy(reason, r.reason.data(), std::min(r.reason.size(), kReasonBytes));
  write_at(frame_, index, &r.frame, H5T_NATIVE_INT);
  write_at(method_, index, method, names);
  write_at(iterations_, index, &r.iterations, H5T_NATIVE_INT);
  write_at(schedule_, index, schedule, names);
  write_at(y_, index, &r.y, H5T_NATIVE_DOUBLE);
  write_at(previous_y_, index, &r.previous_y, H5T_NATIVE_DOUBLE);
  write_at(y_floor_, index, &r.y_floor, H5T_NATIVE_DOUBLE);
  write_at(predicted_, index, &r.predicted_ms, H5T_NATIVE_DOUBLE);
  write_at(measured_, index, &r.measured_ms, H5T_NATIVE_DOUBLE);
  write_at(check_, index, &r.check_ms, H5T_NATIVE_DOUBLE);
  write_at(changed_, index, &r.changed, H5T_NATIVE_INT);
  write_at(reason_, index, reason, reasons);
}

void DecisionSeries::append(const DecisionRecord& row) {
  rows_.push_back(row);
  write_row(rows_.size() - 1, true);
}

void DecisionSeries::set_last_measured(double measured_ms) {
  if (rows_.empty()) return;
  rows_.back().measured_ms = measured_ms;
  write_at(measured_, rows_.size() - 1, &measured_ms, H5T_NATIVE_DOUBLE);
}

void DecisionSeries::close(bool abandon) {
  for (const Column& c : kColumns) {
    if (abandon) {
      (void)(this->*c.member).release();
    } else {
      (this->*c.member).reset();
    }
  }
}

std::vector<DecisionRecord> read_decisions(hid_t file) {
  if (H5Lexists(file, "decisions", H5P_DEFAULT) <= 0) return {};
  H5Handle g = h5_check(H5Gopen2(file, "decisions", H5P_DEFAULT), H5Gclose, "opening /decisions");
  H5Handle frame = open_set(g, "frame");
  const std::size_t n = rows_of(frame);
  const auto frames = read_all<int>(frame, H5T_NATIVE_INT, n);
  const auto iterations = read_all<int>(open_set(g, "iterations"), H5T_NATIVE_INT, n);
  const auto changed = read_all<int>(open_set(g, "changed"), H5T_NATIVE_INT, n);
  const auto y = read_all<double>(open_set(g, "y"), H5T_NATIVE_DOUBLE, n);
  const auto previous_y = read_all<double>(open_set(g, "previous_y"), H5T_NATIVE_DOUBLE, n);
  const auto y_floor = read_all<double>(open_set(g, "y_floor"), H5T_NATIVE_DOUBLE, n);
  const auto predicted = read_all<double>(open_set(g, "predicted_ms"), H5T_NATIVE_DOUBLE, n);
  const auto measured = read_all<double>(open_set(g, "measured_ms"), H5T_NATIVE_DOUBLE, n);
  const auto check = read_all<double>(open_set(g, "check_ms"), H5T_NATIVE_DOUBLE, n);
  const auto method = read_strings(open_set(g, "method"), kNameBytes, n);
  const auto schedule = read_strings(open_set(g, "schedule"), kNameBytes, n);
  const auto reason = read_strings(open_set(g, "reason"), kReasonBytes, n);
  std::vector<DecisionRecord> rows(n);
  for (std::size_t i = 0; i < n; ++i) {
    rows[i] = {frames[i],  method[i],    iterations[i], schedule[i], y[i],       previous_y[i],
               y_floor[i], predicted[i], measured[i],   check[i],    changed[i], reason[i]};
  }
  return rows;
}

}  // namespace atssim::io
