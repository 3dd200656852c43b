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

void write_devices(hid_t file, const std::vector<DeviceRecord>& devices) {
  H5Handle g = create_group(file, "devices");
  std::vector<std::string> name, vendor, type, platform, version, svm;
  std::vector<int> units, index, sub;
  for (const auto& d : devices) {
    name.push_back(d.name);
    vendor.push_back(d.vendor);
    type.push_back(d.type);
    platform.push_back(d.platform);
    version.push_back(d.version);
    svm.push_back(d.svm);
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

void write_schedule_info(hid_t file, const ScheduleInfo& info, std::size_t devices) {
  H5Handle g = create_group(file, "schedule");
  write_string_attribute(g, "mode", info.mode);
  write_string_attribute(g, "executor", info.executor);
  write_string_attribute(g, "memory", info.memory);
  H5Handle tasks = create_group(g, "tasks");
  std::vector<std::string> name, kind;
  std::vector<int> iteration, block, part;
  for (const TaskRecord& t : info.tasks) {
    name.push_back(t.name);
    kind.push_back(t.kind);
    iteration.push_back(t.iteration);
    block.push_back(t.block);
    part.push_back(t.part);
  }
  write_string_array(tasks, "name", name);
  write_string_array(tasks, "kind", kind);
  write_int_array(tasks, "iteration", iteration, 0);
  write_int_array(tasks, "block", block, 0);
  write_int_array(tasks, "part", part, 0);
  std::vector<int> from, to;
  for (const auto& [a, b] : info.edges) {
    from.push_back(a);
    to.push_back(b);
  }
  write_int_array(tasks, "edge_from", from, 0);
  write_int_array(tasks, "edge_to", to, 0);
  H5Handle dev = h5_check(H5Gopen2(file, "devices", H5P_DEFAULT), H5Gclose, "/devices");
  if (info.costs.tasks > 0) write_double_array(dev, "costs_ms", info.costs.ms, info.costs.devices);
  if (!info.latency_ms.empty()) write_double_array(dev, "latency_ms", info.latency_ms, devices);
  if (!info.ms_per_byte.empty()) write_double_array(dev, "ms_per_byte", info.ms_per_byte, devices);
  if (!info.split_fractions.empty()) write_double_array(dev, "split_fractions", info.split_fractions, 0);
}

void write_mesh(hid_t file, std::span<const model::ObjectRange> objects) {
  H5Handle mesh = create_group(file, "mesh");
  for (const auto& obj : objects) {
    H5Handle g = create_group(mesh, obj.name);
    std::vector<float> rest;
    for (const auto& p : obj.rest_position) rest.insert(rest.end(), {float(p.x()), float(p.y()), float(p.z())});
    std::vector<int> tris;
    for (const auto& t : obj.triangles) tris.insert(tris.end(), t.begin(), t.end());
    write_float_array(g, "rest_positions", rest, 3);
    write_int_array(g, "triangles", tris, 3);
    write_int_array(g, "pinned", obj.pinned, 0);
    std::vector<int> tets;
    for (const auto& t : obj.tetrahedra) tets.insert(tets.end(), t.begin(), t.end());
    write_int_array(g, "tetrahedra", tets, 4);  // [k, 4]; empty for cloth
    write_int_attribute(g, "vertex_offset", obj.vertex_offset);
    write_int_attribute(g, "vertex_count", obj.vertex_count);
  }
}

}  // namespace

ResultWriter::ResultWriter(const std::string& path, const RunInfo& info, std::span<const model::ObjectRange> objects)
    : path_(path) {
  for (const auto& obj : objects) object_names_.push_back(obj.name);
  for (const auto& obj : objects) particles_ = std::max<std::size_t>(particles_, obj.vertex_offset + obj.vertex_count);
  // SWMR needs the latest file format; readers are h5py/HDF5 ≥ 1.10.
  H5Handle fapl = h5_check(H5Pcreate(H5P_FILE_ACCESS), H5Pclose, "file access properties");
  h5_check(H5Pset_libver_bounds(fapl, H5F_LIBVER_LATEST, H5F_LIBVER_LATEST), "file format bounds");
  const hid_t id = H5Fcreate(path.c_str(), H5F_ACC_TRUNC, H5P_DEFAULT, fapl);
  if (id < 0) {
    throw input_error(
        fmt::format("cannot create output file '{}': check that its folder exists and is writable "
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
  write_schedule_info(file_, info.schedule, info.devices.size());
  write_mesh(file_, objects);

  H5Handle frames = create_group(file_, "frames");
  time_ = create_series(frames, "time", 0, 0, H5T_IEEE_F64LE);
  positions_ = create_series(frames, "positions", particles_, 3, H5T_IEEE_F32LE);
  H5Handle timing = create_group(file_, "timing");
  frame_ms_ = create_series(timing, "frame_ms", 0, 0, H5T_IEEE_F64LE);
  schedule_ms_ = create_series(timing, "schedule_ms", 0, 0, H5T_IEEE_F64LE);
  H5Handle sched = h5_check(H5Gopen2(file_, "schedule", H5P_DEFAULT), H5Gclose, "/schedule");
  sched_frame_ = create_series(sched, "frame", 0, 0, H5T_STD_I32LE);
  sched_task_ = create_series(sched, "task", 0, 0, H5T_STD_I32LE);
  sched_device_ = create_series(sched, "device", 0, 0, H5T_STD_I32LE);
  sched_pstart_ = create_series(sched, "predicted_start_ms", 0, 0, H5T_IEEE_F64LE);
  sched_pfinish_ = create_series(sched, "predicted_finish_ms", 0, 0, H5T_IEEE_F64LE);
  sched_mstart_ = create_series(sched, "measured_start_ms", 0, 0, H5T_IEEE_F64LE);
  sched_mfinish_ = create_series(sched, "measured_finish_ms", 0, 0, H5T_IEEE_F64LE);
  H5Handle waits = create_group(sched, "waits");
  wait_frame_ = create_series(waits, "frame", 0, 0, H5T_STD_I32LE);
  wait_producer_ = create_series(waits, "producer", 0, 0, H5T_STD_I32LE);
  wait_consumer_ = create_series(waits, "consumer", 0, 0, H5T_STD_I32LE);
  wait_pdevice_ = create_series(waits, "producer_device", 0, 0, H5T_STD_I32LE);
  wait_cdevice_ = create_series(waits, "consumer_device", 0, 0, H5T_STD_I32LE);
  H5Handle makespan = create_group(sched, "makespan");
  mk_frame_ = create_series(makespan, "frame", 0, 0, H5T_STD_I32LE);
  mk_predicted_ = create_series(makespan, "predicted_ms", 0, 0, H5T_IEEE_F64LE);
  mk_measured_ = create_series(makespan, "measured_ms", 0, 0, H5T_IEEE_F64LE);
  mk_bytes_ = create_series(makespan, "bytes_moved", 0, 0, H5T_STD_U64LE);
  H5Handle contact = create_group(file_, "contact");
  contact_active_ = create_series(contact, "active", 0, 0, H5T_STD_I32LE);
  contact_min_distance_ = create_series(contact, "min_distance", 0, 0, H5T_IEEE_F64LE);
  contact_max_penetration_ = create_series(contact, "max_penetration", 0, 0, H5T_IEEE_F64LE);
  views_ = write_xdmf_cells(file_, objects, particles_);

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
  const double one[1] = {value};
  append_rows<double>(set, one, H5T_NATIVE_DOUBLE, static_cast<hsize_t>(frames_));
}

template <typename T>
void ResultWriter::append_rows(hid_t set, std::span<const T> values, hid_t mem_type, hsize_t rows) {
  if (values.empty()) return;
  const hsize_t size[1] = {rows + values.size()};
  h5_check(H5Dset_extent(set, size), "extending a series");
  H5Handle space = h5_check(H5Dget_space(set), H5Sclose, "series space");
  const hsize_t start[1] = {rows}, count[1] = {values.size()};
  h5_check(H5Sselect_hyperslab(space, H5S_SELECT_SET, start, nullptr, count, nullptr), "selecting rows");
  H5Handle mem = h5_check(H5Screate_simple(1, count, nullptr), H5Sclose, "memory space");
  h5_check(H5Dwrite(set, mem_type, mem, space, H5P_DEFAULT, values.data()), "writing rows of a series");
}

void ResultWriter::append_schedule(int frame, std::span<const ScheduledTask> tasks, std::span<const sched::Wait> waits,
                                   double predicted_makespan_ms, double measured_makespan_ms, std::size_t bytes_moved) {
  std::vector<int> f(tasks.size(), frame), task, device;
  std::vector<double> ps, pf, ms, mf;
  for (const ScheduledTask& t : tasks) {
    task.push_back(static_cast<int>(t.task));
    device.push_back(t.device);
    ps.push_back(t.predicted_start_ms);
    pf.push_back(t.predicted_finish_ms);
    ms.push_back(t.measured_start_ms);
    mf.push_back(t.measured_finish_ms);
  }
  hsize_t rows = sched_rows_;
  append_rows<int>(sched_frame_, f, H5T_NATIVE_INT, rows);
  append_rows<int>(sched_task_, task, H5T_NATIVE_INT, rows);
  append_rows<int>(sched_device_, device, H5T_NATIVE_INT, rows);
  append_rows<double>(sched_pstart_, ps, H5T_NATIVE_DOUBLE, rows);
  append_rows<double>(sched_pfinish_, pf, H5T_NATIVE_DOUBLE, rows);
  append_rows<double>(sched_mstart_, ms, H5T_NATIVE_DOUBLE, rows);
  append_rows<double>(sched_mfinish_, mf, H5T_NATIVE_DOUBLE, rows);
  sched_rows_ += tasks.size();

  std::vector<int> wf(waits.size(), frame), producer, consumer, pdev, cdev;
  for (const sched::Wait& w : waits) {
    producer.push_back(static_cast<int>(w.producer));
    consumer.push_back(static_cast<int>(w.consumer));
    pdev.push_back(static_cast<int>(w.producer_device));
    cdev.push_back(static_cast<int>(w.consumer_device));
  }
  rows = wait_rows_;
  append_rows<int>(wait_frame_, wf, H5T_NATIVE_INT, rows);
  append_rows<int>(wait_producer_, producer, H5T_NATIVE_INT, rows);
  append_rows<int>(wait_consumer_, consumer, H5T_NATIVE_INT, rows);
  append_rows<int>(wait_pdevice_, pdev, H5T_NATIVE_INT, rows);
  append_rows<int>(wait_cdevice_, cdev, H5T_NATIVE_INT, rows);
  wait_rows_ += waits.size();

  rows = makespan_rows_;
  const int fr[1] = {frame};
  const double p[1] = {predicted_makespan_ms}, m[1] = {measured_makespan_ms};
  append_rows<int>(mk_frame_, fr, H5T_NATIVE_INT, rows);
  append_rows<double>(mk_predicted_, p, H5T_NATIVE_DOUBLE, rows);
  append_rows<double>(mk_measured_, m, H5T_NATIVE_DOUBLE, rows);
  const std::uint64_t b[1] = {bytes_moved};
  append_rows<std::uint64_t>(mk_bytes_, b, H5T_NATIVE_UINT64, rows);
  makespan_rows_ += 1;
}

void ResultWriter::append_frame(double time, std::span<const float> xyz, double frame_ms, double schedule_ms,
                                const ContactFrame& contact) {
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
  append_scalar(schedule_ms_, schedule_ms);
  const std::int32_t active[1] = {contact.active};
  append_rows<std::int32_t>(contact_active_, active, H5T_NATIVE_INT32, static_cast<hsize_t>(frames_));
  append_scalar(contact_min_distance_, contact.min_distance);
  append_scalar(contact_max_penetration_, contact.max_penetration);
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
  for (H5Handle* h : {&frame_ms_,       &schedule_ms_,          &sched_frame_,
                      &sched_task_,     &sched_device_,         &sched_pstart_,
                      &sched_pfinish_,  &sched_mstart_,         &sched_mfinish_,
                      &wait_frame_,     &wait_producer_,        &wait_consumer_,
                      &wait_pdevice_,   &wait_cdevice_,         &mk_frame_,
                      &mk_predicted_,   &mk_measured_,          &mk_bytes_,
                      &contact_active_, &contact_min_distance_, &contact_max_penetration_}) {
    h->reset();
  }
  file_.reset();
  // Attributes cannot be added in SWMR mode: reopen to record the outcome.
  // Without file locking: a SWMR reader (a notebook watching the run) holds
  // a lock that would make the reopen, and so the whole run, fail.
  H5Handle fapl = h5_check(H5Pcreate(H5P_FILE_ACCESS), H5Pclose, "file access properties");
  h5_check(H5Pset_file_locking(fapl, false, true), "file locking");
  H5Handle file = h5_check(H5Fopen(path_.c_str(), H5F_ACC_RDWR, fapl), H5Fclose, "reopening " + path_);
  write_frame_views(file, views_, static_cast<std::size_t>(frames_));
  write_int_attribute(file, "complete", complete ? 1 : 0);
  write_string_attribute(file, "error", error);
  file.reset();
  write_xdmf();
}

std::string ResultWriter::xdmf_path() const { return std::filesystem::path(path_).replace_extension(".xdmf").string(); }

void ResultWriter::write_xdmf() const {
  write_xdmf_file(xdmf_path(), std::filesystem::path(path_).filename().string(), views_, object_names_, times_);
}

}  // namespace atssim::io
