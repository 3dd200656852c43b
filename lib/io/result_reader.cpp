#include "io/result_reader.hpp"

#include <filesystem>

#include <fmt/format.h>

#include "io/decision_series.hpp"
#include "io/h5_errors.hpp"
#include "io/h5_handle.hpp"
#include "util/error.hpp"

namespace atssim::io {

namespace {

H5Handle open_file(const std::string& path) {
  if (!std::filesystem::exists(path)) throw input_error(fmt::format("{}: file does not exist", path));
  quiet_hdf5();
  // Plain read-only (the writer uses no SWMR); files of atssim versions that
  // wrote under SWMR open in SWMR mode.
  hid_t id = -1;
  H5E_BEGIN_TRY { id = H5Fopen(path.c_str(), H5F_ACC_RDONLY, H5P_DEFAULT); }
  H5E_END_TRY;
  if (id < 0) {
    H5E_BEGIN_TRY { id = H5Fopen(path.c_str(), H5F_ACC_RDONLY | H5F_ACC_SWMR_READ, H5P_DEFAULT); }
    H5E_END_TRY;
  }
  if (id < 0) throw input_error(fmt::format("{}: not an HDF5 file (or damaged)", path));
  return H5Handle(id, H5Fclose);
}

std::string string_attribute(hid_t obj, const char* name) {
  if (H5Aexists(obj, name) <= 0) return "";
  H5Handle attr = h5_check(H5Aopen(obj, name, H5P_DEFAULT), H5Aclose, name);
  H5Handle type = h5_check(H5Aget_type(attr), H5Tclose, name);
  std::string value(H5Tget_size(type), '\0');
  h5_check(H5Aread(attr, type, value.data()), name);
  value.resize(value.find('\0') == std::string::npos ? value.size() : value.find('\0'));
  return value;
}

std::vector<hsize_t> dims_of(hid_t set) {
  H5Handle space = h5_check(H5Dget_space(set), H5Sclose, "space");
  const int rank = H5Sget_simple_extent_ndims(space);
  std::vector<hsize_t> dims(std::max(rank, 0));
  H5Sget_simple_extent_dims(space, dims.data(), nullptr);
  return dims;
}

std::vector<double> read_doubles(hid_t file, const char* name) {
  H5Handle set = h5_check(H5Dopen2(file, name, H5P_DEFAULT), H5Dclose, name);
  const auto dims = dims_of(set);
  std::vector<double> v(dims.empty() ? 0 : dims[0]);
  if (!v.empty()) h5_check(H5Dread(set, H5T_NATIVE_DOUBLE, H5S_ALL, H5S_ALL, H5P_DEFAULT, v.data()), name);
  return v;
}

std::vector<std::string> read_strings(hid_t file, const char* name) {
  H5Handle set = h5_check(H5Dopen2(file, name, H5P_DEFAULT), H5Dclose, name);
  H5Handle type = h5_check(H5Dget_type(set), H5Tclose, name);
  const std::size_t width = H5Tget_size(type);
  const auto dims = dims_of(set);
  const std::size_t n = dims.empty() ? 0 : dims[0];
  std::vector<char> raw(width * n);
  if (n > 0) h5_check(H5Dread(set, type, H5S_ALL, H5S_ALL, H5P_DEFAULT, raw.data()), name);
  std::vector<std::string> out;
  for (std::size_t i = 0; i < n; ++i) {
    std::string s(raw.data() + i * width, width);
    out.push_back(s.substr(0, s.find('\0')));
  }
  return out;
}

}  // namespace

ResultSummary read_summary(const std::string& path) {
  H5Handle file = open_file(path);
  ResultSummary s;
  s.format = string_attribute(file, "format");
  if (s.format != "atssim") throw input_error(fmt::format("{}: not an atssim result file (no format=atssim)", path));
  s.format_version = read_int_attribute(file, "format_version");
  s.atssim_version = string_attribute(file, "atssim_version");
  s.command_line = string_attribute(file, "command_line");
  s.created = string_attribute(file, "created");
  s.complete = read_int_attribute(file, "complete") != 0;
  s.error = string_attribute(file, "error");
  s.time = read_doubles(file, "/frames/time");
  s.frame_ms = read_doubles(file, "/timing/frame_ms");
  H5Handle pos = h5_check(H5Dopen2(file, "/frames/positions", H5P_DEFAULT), H5Dclose, "/frames/positions");
  const auto dims = dims_of(pos);
  s.frames = dims.size() == 3 ? dims[0] : 0;
  s.particles = dims.size() == 3 ? dims[1] : 0;
  s.devices = read_strings(file, "/devices/name");
  H5Handle mesh = h5_check(H5Gopen2(file, "/mesh", H5P_DEFAULT), H5Gclose, "/mesh");
  H5G_info_t info{};
  H5Gget_info(mesh, &info);
  for (hsize_t i = 0; i < info.nlinks; ++i) {
    char name[256] = {};
    H5Lget_name_by_idx(mesh, ".", H5_INDEX_NAME, H5_ITER_INC, i, name, sizeof(name), H5P_DEFAULT);
    s.objects.emplace_back(name);
  }
  return s;
}

std::vector<double> read_series(const std::string& path, const std::string& dataset) {
  H5Handle file = open_file(path);
  return read_doubles(file, dataset.c_str());
}

std::vector<float> read_frame_positions(const std::string& path, std::size_t frame) {
  H5Handle file = open_file(path);
  H5Handle set = h5_check(H5Dopen2(file, "/frames/positions", H5P_DEFAULT), H5Dclose, "/frames/positions");
  const auto dims = dims_of(set);
  if (dims.size() != 3 || frame >= dims[0]) {
    throw input_error(fmt::format("{}: frame {} does not exist ({} frames)", path, frame, dims.empty() ? 0 : dims[0]));
  }
  H5Handle space = h5_check(H5Dget_space(set), H5Sclose, "space");
  const hsize_t start[3] = {frame, 0, 0}, count[3] = {1, dims[1], 3};
  h5_check(H5Sselect_hyperslab(space, H5S_SELECT_SET, start, nullptr, count, nullptr), "select");
  H5Handle mem = h5_check(H5Screate_simple(3, count, nullptr), H5Sclose, "memory space");
  std::vector<float> xyz(dims[1] * 3);
  h5_check(H5Dread(set, H5T_NATIVE_FLOAT, mem, space, H5P_DEFAULT, xyz.data()), "reading positions");
  return xyz;
}

Checkpoint read_checkpoint(const std::string& path) {
  H5Handle file = open_file(path);
  const std::optional<CheckpointSlots> slots = CheckpointSlots::open(file);
  std::optional<Checkpoint> point;
  if (slots) {
    H5Handle set = h5_check(H5Dopen2(file, "/frames/positions", H5P_DEFAULT), H5Dclose, "/frames/positions");
    point = slots->newest(static_cast<long long>(dims_of(set).at(0)));
  }
  if (!point) {
    throw input_error(
        fmt::format("{}: holds no checkpoint (a run killed before its first frame, or not written by "
                    "atssim run)",
                    path));
  }
  return *point;
}

std::vector<DecisionRecord> read_decisions(const std::string& path) {
  H5Handle file = open_file(path);
  return read_decisions(file.get());
}

}  // namespace atssim::io
