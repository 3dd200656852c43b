#include "io/result_writer.hpp"

#include <algorithm>
#include <chrono>
#include <filesystem>

#include <fmt/chrono.h>
#include <fmt/format.h>

#include "io/xdmf_writer.hpp"
#include "util/error.hpp"

#ifndef ATSSIM_VERSION
#define ATSSIM_VERSION "0.0.0"
#endif

namespace atssim::io {

namespace {

// An extendible 1-D (cols = 0) or [F, rows, cols] dataset, chunked by frame.
H5Handle create_series(hid_t parent, const std::string& name, std::size_t rows, std::size_t cols, hid_t file_type) {
  const int rank = cols == 0 ? 1 : 3;
  hsize_t dims[3] = {0, rows, cols};
  hsize_t max[3] = {H5S_UNLIMITED, rows, cols};
  hsize_t chunk[3] = {hsize_t(cols == 0 ? 256 : 1), rows, cols};
  H5Handle space = h5_check(H5Screate_simple(rank, dims, max), H5Sclose, "series space");
  H5Handle props = h5_check(H5Pcreate(H5P_DATASET_CREATE), H5Pclose, "dataset properties");
  h5_check(H5Pset_chunk(props, rank, chunk), "chunking " + name);
  return h5_check(H5Dcreate2(parent, name.c_str(), file_type, space, H5P_DEFAULT, props, H5P_DEFAULT), H5Dclose,
                  "creating " + name);
}

std::string now_iso8601() {
  const auto now = std::chrono::system_clock::now();
  return fmt::format("{:%Y-%m-%dT%H:%M:%SZ}", fmt::gmtime(std::chrono::system_clock::to_time_t(now)));
}

void write_devices(hid_t file, const std::vector<device::DeviceInfo>& devices) {
  H5Handle g = create_group(file, "devices");
  std::vector<std::string> name, vendor, type, platform, version, svm;
  std::vector<int> units, index, sub;
  for (const auto& d : devices) {
    name.push_back(d.name);
    vendor.push_back(d.vendor);
    type.push_back(d.type);
    platform.push_back(d.platform);
    version.push_back(d.version);
    svm.push_back(device::svm_text(d.svm));
    units.push_back(d.compute_units);
    index.push_back(d.index);
    sub.push_back(d.sub_device);
  }
  write_string_array(g, "name", name);
  write_string_array(g, "vendor", vendor);
  write_string_array(g, "type", type);
  write_string_array(g, "platform", platform);
  write_string_array(g, "version", version);
  write_string_array(g, "svm", svm);
  write_int_array(g, "compute_units", units, 0);
  write_int_array(g, "index", index, 0);
  write_int_array(g, "sub_device", sub, 0);
}

void write_mesh(hid_t file, const model::Model& model) {
  H5Handle mesh = create_group(file, "mesh");
  for (const auto& obj : model.objects) {
    H5Handle g = create_group(mesh, obj.name);
    std::vector<float> rest;
    for (const auto& p : obj.rest_position) rest.insert(rest.end(), {float(p.x()), float(p.y()), float(p.z())});
    std::vector<int> tris;
    for (const auto& t : obj.triangles) tris.insert(tris.end(), t.begin(), t.end());
    write_float_array(g, "rest_positions", rest, 3);
    write_int_array(g, "triangles", tris, 3);
    write_int_array(g, "pinned", obj.pinned, 0);
    write_int_attribute(g, "vertex_offset", obj.vertex_offset);
    write_int_attribute(g, "vertex_count", obj.vertex_count);
  }
}

}  // namespace

ResultWriter::ResultWriter(const std::string& path, const RunInfo& info, const model::Model& model)
    : path_(path), objects_(model.objects) {
  for (const auto& obj : objects_) particles_ = std::max<std::size_t>(particles_, obj.vertex_offset + obj.vertex_count);
  // SWMR needs the latest file format; readers are h5py/HDF5 ≥ 1.10.
  H5Handle fapl = h5_check(H5Pcreate(H5P_FILE_ACCESS), H5Pclose, "file access properties");
  h5_check(H5Pset_libver_bounds(fapl, H5F_LIBVER_LATEST, H5F_LIBVER_LATEST), "file format bounds");
  const hid_t id = H5Fcreate(path.c_str(), H5F_ACC_TRUNC, H5P_DEFAULT, fapl);
  if (id < 0) {
    throw input_error(fmt::format("cannot create output file '{}': check that its folder exists and is writable "
                                  "(or pass -o elsewhere)",
                                  path));
  }
  file_ = H5Handle(id, H5Fclose);
  write_string_attribute(file_, "format", "atssim");
  write_int_attribute(file_, "format_version", kFormatVersion);
  write_string_attribute(file_, "atssim_version", ATSSIM_VERSION);
  write_string_attribute(file_, "command_line", info.command_line);
  write_string_attribute(file_, "created", now_iso8601());
  write_int_attribute(file_, "complete", 0);
  write_string_attribute(file_, "error", "");

  H5Handle scene = create_group(file_, "scene");
  write_string_dataset(scene, "yaml", info.scene_yaml);
  write_string_dataset(scene, "resolved", info.resolved_yaml);
  write_devices(file_, info.devices);
  write_mesh(file_, model);

  H5Handle frames = create_group(file_, "frames");
  time_ = create_series(frames, "time", 0, 0, H5T_IEEE_F64LE);
  positions_ = create_series(frames, "positions", particles_, 3, H5T_IEEE_F32LE);
  H5Handle timing = create_group(file_, "timing");
  frame_ms_ = create_series(timing, "frame_ms", 0, 0, H5T_IEEE_F64LE);

  h5_check(H5Fstart_swmr_write(file_), "starting single-writer/multi-reader mode");
  write_xdmf();
}

ResultWriter::~ResultWriter() {
  if (!closed_) {
    try {
      close_with(false, "the run ended without finishing");
    } catch (...) {
    }
  }
}

void ResultWriter::append_scalar(hid_t set, double value) {
  const hsize_t size[1] = {static_cast<hsize_t>(frames_ + 1)};
  h5_check(H5Dset_extent(set, size), "extending a series");
  H5Handle space = h5_check(H5Dget_space(set), H5Sclose, "series space");
  const hsize_t start[1] = {static_cast<hsize_t>(frames_)}, count[1] = {1};
  h5_check(H5Sselect_hyperslab(space, H5S_SELECT_SET, start, nullptr, count, nullptr), "selecting a frame");
  H5Handle mem = h5_check(H5Screate_simple(1, count, nullptr), H5Sclose, "memory space");
  h5_check(H5Dwrite(set, H5T_NATIVE_DOUBLE, mem, space, H5P_DEFAULT, &value), "writing a frame value");
}

void ResultWriter::append_frame(double time, std::span<const float> xyz, double frame_ms) {
  if (xyz.size() != particles_ * 3) {
    throw Error(fmt::format("output: frame has {} values, expected {}", xyz.size(), particles_ * 3));
  }
  const hsize_t size[3] = {static_cast<hsize_t>(frames_ + 1), particles_, 3};
  h5_check(H5Dset_extent(positions_, size), "extending /frames/positions");
  H5Handle space = h5_check(H5Dget_space(positions_), H5Sclose, "positions space");
  const hsize_t start[3] = {static_cast<hsize_t>(frames_), 0, 0}, count[3] = {1, particles_, 3};
  h5_check(H5Sselect_hyperslab(space, H5S_SELECT_SET, start, nullptr, count, nullptr), "selecting a frame");
  H5Handle mem = h5_check(H5Screate_simple(3, count, nullptr), H5Sclose, "memory space");
  h5_check(H5Dwrite(positions_, H5T_NATIVE_FLOAT, mem, space, H5P_DEFAULT, xyz.data()), "writing positions");
  append_scalar(time_, time);
  times_.push_back(time);
  append_scalar(frame_ms_, frame_ms);
  ++frames_;
  h5_check(H5Fflush(file_, H5F_SCOPE_GLOBAL), "flushing the output file");
  // The sidecar grows with the frame count; rewrite it at powers of two.
  if ((frames_ & (frames_ - 1)) == 0) write_xdmf();
}

void ResultWriter::finish() { close_with(true, ""); }
void ResultWriter::fail(const std::string& error) { close_with(false, error); }

void ResultWriter::close_with(bool complete, const std::string& error) {
  if (closed_) return;
  closed_ = true;
  positions_.reset();
  time_.reset();
  frame_ms_.reset();
  file_.reset();
  // Attributes cannot be added in SWMR mode: reopen to record the outcome.
  H5Handle file = h5_check(H5Fopen(path_.c_str(), H5F_ACC_RDWR, H5P_DEFAULT), H5Fclose, "reopening " + path_);
  write_int_attribute(file, "complete", complete ? 1 : 0);
  write_string_attribute(file, "error", error);
  file.reset();
  write_xdmf();
}

std::string ResultWriter::xdmf_path() const {
  return std::filesystem::path(path_).replace_extension(".xdmf").string();
}

void ResultWriter::write_xdmf() const {
  write_xdmf_file(xdmf_path(), std::filesystem::path(path_).filename().string(), objects_, particles_, times_);
}

}  // namespace atssim::io
