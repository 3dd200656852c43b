#include "io/result_writer.hpp"

#include <sys/stat.h>
#include <sys/statvfs.h>
#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <filesystem>
#include <sstream>
#include <stdexcept>

#include <fmt/chrono.h>
#include <fmt/format.h>

#include "io/h5_errors.hpp"
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

std::string partial_path(const std::string& path) {
  std::filesystem::path p(path);
  // Without an extension the sidecars would collide ("out" and "out.partial" -> "out.xdmf").
  const std::string ext = p.has_extension() ? p.extension().string() : std::string(".h5");
  return p.replace_extension().string() + ".partial" + ext;
}

namespace {

void check_output_folder(const std::string& path) {
  if (path.empty()) throw input_error("the output path is empty: pass -o FILE.h5 or set output.path");
  const std::filesystem::path p(path);
  std::error_code ec;
  if (std::filesystem::is_directory(p, ec)) {
    throw input_error(fmt::format("output '{}' is a folder: pass -o with a file name, e.g. -o {}/run.h5", path, path));
  }
  const std::filesystem::path folder = p.has_parent_path() ? p.parent_path() : std::filesystem::path(".");
  if (!std::filesystem::is_directory(folder, ec)) {
    throw input_error(
        fmt::format("cannot create output file '{}': its folder '{}' does not exist (make it, or pass "
                    "-o elsewhere)",
                    path, folder.string()));
  }
  if (::access(folder.c_str(), W_OK) != 0) {
    throw input_error(
        fmt::format("cannot create output file '{}': its folder '{}' is not writable (pass -o "
                    "elsewhere)",
                    path, folder.string()));
  }
  if (std::filesystem::exists(p, ec) && !std::filesystem::is_regular_file(p, ec)) {
    throw input_error(fmt::format("output '{}' exists and is not a regular file: pass -o elsewhere", path));
  }
}

// Without HDF5's file locking: a reader (a notebook watching the run, or
// `atssim inspect`) may open the file while it is written; OutputLock keeps
// other writers out.
H5Handle file_access() {
  H5Handle fapl = h5_check(H5Pcreate(H5P_FILE_ACCESS), H5Pclose, "file access properties");
  h5_check(H5Pset_file_locking(fapl, false, true), "file locking");
  return fapl;
}

// /scene/resolved without the keys a resumed run may change (frames, output path).
std::string resumable_part(const std::string& resolved) {
  std::string out, line;
  std::istringstream in(resolved);
  while (std::getline(in, line)) {
    const auto key = line.find_first_not_of(' ');
    if (key != std::string::npos && (line.compare(key, 7, "frames:") == 0 || line.compare(key, 5, "path:") == 0))
      continue;
    out += line + "\n";
  }
  return out;
}

std::string read_string_dataset(hid_t file, const char* name) {
  H5Handle set = h5_check(H5Dopen2(file, name, H5P_DEFAULT), H5Dclose, name);
  H5Handle type = h5_check(H5Dget_type(set), H5Tclose, name);
  std::string value(H5Tget_size(type), '\0');
  h5_check(H5Dread(set, type, H5S_ALL, H5S_ALL, H5P_DEFAULT, value.data()), name);
  return value.substr(0, value.find('\0'));
}

long long read_int_attribute(hid_t object, const char* name) {
  if (H5Aexists(object, name) <= 0) return 0;
  H5Handle attr = h5_check(H5Aopen(object, name, H5P_DEFAULT), H5Aclose, name);
  long long v = 0;
  h5_check(H5Aread(attr, H5T_NATIVE_LLONG, &v), name);
  return v;
}

hsize_t rows_of(hid_t set) {
  H5Handle space = h5_check(H5Dget_space(set), H5Sclose, "series space");
  hsize_t dims[3] = {0, 0, 0};
  H5Sget_simple_extent_dims(space, dims, nullptr);
  return dims[0];
}

void truncate_rows(hid_t set, hsize_t rows) {
  H5Handle space = h5_check(H5Dget_space(set), H5Sclose, "series space");
  hsize_t dims[3] = {0, 0, 0};
  const int rank = H5Sget_simple_extent_dims(space, dims, nullptr);
  if (rank < 1 || dims[0] == rows) return;
  dims[0] = rows;
  h5_check(H5Dset_extent(set, dims), "truncating a series");
}

}  // namespace

ResultWriter::ResultWriter(const std::string& path, const RunInfo& info, std::span<const model::ObjectRange> objects,
                           Checkpoint* resume)
    : path_(path) {
  quiet_hdf5();
  check_output_folder(path);
  lock_ = std::make_unique<OutputLock>(path);
  for (const auto& obj : objects) object_names_.push_back(obj.name);
  for (const auto& obj : objects) particles_ = std::max<std::size_t>(particles_, obj.vertex_offset + obj.vertex_count);
  if (resume != nullptr) {
    reopen(info, *resume);
  } else {
    create(info, objects);
  }
  struct stat st {};
  if (::stat(writing_.c_str(), &st) == 0) {
    device_ = st.st_dev;
    inode_ = st.st_ino;
  }
  xdmf_ = XdmfStream(xdmf_path(), std::filesystem::path(writing_).filename().string(), views_, object_names_, times_);
}

void ResultWriter::create(const RunInfo& info, std::span<const model::ObjectRange> objects) {
  std::error_code ec;
  writing_ = std::filesystem::exists(path_, ec) ? partial_path(path_) : path_;
  // The default (oldest) format bounds: a superblock without the
  // "open for writing" flags that would refuse readers after a kill.
  H5Handle fapl = file_access();
  const hid_t id = H5Fcreate(writing_.c_str(), H5F_ACC_TRUNC, H5P_DEFAULT, fapl);
  if (id < 0) {
    throw runtime_error(
        fmt::format("cannot create output file '{}': {} (pass -o elsewhere)", writing_, hdf5_failure()));
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
  create_group(file_, "frames");
  create_group(file_, "timing");
  {
    H5Handle sched = h5_check(H5Gopen2(file_, "schedule", H5P_DEFAULT), H5Gclose, "/schedule");
    create_group(sched, "waits");
    create_group(sched, "makespan");
  }
  create_group(file_, "contact");
  open_series(true);
  views_ = write_xdmf_cells(file_, objects, particles_);
  h5_check(H5Fflush(file_, H5F_SCOPE_GLOBAL), "flushing the output file");
}

void ResultWriter::reopen(const RunInfo& info, Checkpoint& resume) {
  std::error_code ec;
  const std::string partial = partial_path(path_);
  writing_ = std::filesystem::exists(partial, ec) ? partial : path_;
  if (!std::filesystem::exists(writing_, ec)) {
    throw input_error(
        fmt::format("--resume: there is no '{}' (nor '{}') to resume; run without --resume", path_, partial));
  }
  H5Handle fapl = file_access();
  const hid_t id = H5Fopen(writing_.c_str(), H5F_ACC_RDWR, fapl);
  if (id < 0) {
    throw input_error(fmt::format("--resume: cannot open '{}' for writing: {}", writing_, hdf5_failure()));
  }
  file_ = H5Handle(id, H5Fclose);
  if (H5Aexists(file_, "format") <= 0 || H5Lexists(file_, "frames", H5P_DEFAULT) <= 0) {
    throw input_error(fmt::format("--resume: '{}' is not an atssim result file", writing_));
  }
  if (read_int_attribute(file_, "complete") != 0) {
    throw input_error(fmt::format("--resume: '{}' holds a complete run; there is nothing to resume", writing_));
  }
  if (resumable_part(read_string_dataset(file_, "/scene/resolved")) != resumable_part(info.resolved_yaml)) {
    throw input_error(fmt::format(
        "--resume: '{}' was written from a different scene or settings (only simulation.frames and the output "
        "path may change); run without --resume",
        writing_));
  }
  open_series(false);
  auto slots = CheckpointSlots::open(file_);
  const long long available = static_cast<long long>(std::min(rows_of(positions_), rows_of(time_)));
  std::optional<Checkpoint> point = slots ? slots->take_newest(available) : std::nullopt;
  if (!point) {
    throw input_error(
        fmt::format("--resume: '{}' holds no complete checkpoint (it was written by an atssim "
                    "without --resume, or killed before its first frame); run without --resume",
                    writing_));
  }
  checkpoint_ = std::move(*slots);
  frames_ = static_cast<int>(point->frames_written);
  for (hid_t set : {positions_.get(), time_.get(), frame_ms_.get(), schedule_ms_.get(), contact_active_.get(),
                    contact_min_distance_.get(), contact_max_penetration_.get()})
    truncate_rows(set, frames_);
  sched_rows_ = static_cast<hsize_t>(point->schedule_rows);
  wait_rows_ = static_cast<hsize_t>(point->wait_rows);
  makespan_rows_ = static_cast<hsize_t>(point->makespan_rows);
  for (hid_t set : {sched_frame_.get(), sched_task_.get(), sched_device_.get(), sched_pstart_.get(),
                    sched_pfinish_.get(), sched_mstart_.get(), sched_mfinish_.get()})
    truncate_rows(set, sched_rows_);
  for (hid_t set :
       {wait_frame_.get(), wait_producer_.get(), wait_consumer_.get(), wait_pdevice_.get(), wait_cdevice_.get()})
    truncate_rows(set, wait_rows_);
  for (hid_t set : {mk_frame_.get(), mk_predicted_.get(), mk_measured_.get(), mk_bytes_.get()})
    truncate_rows(set, makespan_rows_);
  times_.resize(static_cast<std::size_t>(frames_));
  if (frames_ > 0) {
    H5Handle space = h5_check(H5Dget_space(time_), H5Sclose, "time space");
    h5_check(H5Dread(time_, H5T_NATIVE_DOUBLE, H5S_ALL, H5S_ALL, H5P_DEFAULT, times_.data()), "reading /frames/time");
  }
  views_ = read_xdmf_views(file_, particles_, static_cast<std::size_t>(frames_));
  write_int_attribute(file_, "complete", 0);
  write_string_attribute(file_, "error", "");
  write_string_attribute(file_, "resumed", now_iso8601());
  h5_check(H5Fflush(file_, H5F_SCOPE_GLOBAL), "flushing the output file");
  resume = std::move(*point);
}

// The series, created (a new file) or opened (a resumed one).
void ResultWriter::open_series(bool create_them) {
  struct Series {
    const char* path;
    std::size_t rows, cols;
    hid_t type;
    H5Handle ResultWriter::*member;
  };
  const Series series[] = {
      {"frames/time", 0, 0, H5T_IEEE_F64LE, &ResultWriter::time_},
      {"frames/positions", particles_, 3, H5T_IEEE_F32LE, &ResultWriter::positions_},
      {"timing/frame_ms", 0, 0, H5T_IEEE_F64LE, &ResultWriter::frame_ms_},
      {"timing/schedule_ms", 0, 0, H5T_IEEE_F64LE, &ResultWriter::schedule_ms_},
      {"schedule/frame", 0, 0, H5T_STD_I32LE, &ResultWriter::sched_frame_},
      {"schedule/task", 0, 0, H5T_STD_I32LE, &ResultWriter::sched_task_},
      {"schedule/device", 0, 0, H5T_STD_I32LE, &ResultWriter::sched_device_},
      {"schedule/predicted_start_ms", 0, 0, H5T_IEEE_F64LE, &ResultWriter::sched_pstart_},
      {"schedule/predicted_finish_ms", 0, 0, H5T_IEEE_F64LE, &ResultWriter::sched_pfinish_},
      {"schedule/measured_start_ms", 0, 0, H5T_IEEE_F64LE, &ResultWriter::sched_mstart_},
      {"schedule/measured_finish_ms", 0, 0, H5T_IEEE_F64LE, &ResultWriter::sched_mfinish_},
      {"schedule/waits/frame", 0, 0, H5T_STD_I32LE, &ResultWriter::wait_frame_},
      {"schedule/waits/producer", 0, 0, H5T_STD_I32LE, &ResultWriter::wait_producer_},
      {"schedule/waits/consumer", 0, 0, H5T_STD_I32LE, &ResultWriter::wait_consumer_},
      {"schedule/waits/producer_device", 0, 0, H5T_STD_I32LE, &ResultWriter::wait_pdevice_},
      {"schedule/waits/consumer_device", 0, 0, H5T_STD_I32LE, &ResultWriter::wait_cdevice_},
      {"schedule/makespan/frame", 0, 0, H5T_STD_I32LE, &ResultWriter::mk_frame_},
      {"schedule/makespan/predicted_ms", 0, 0, H5T_IEEE_F64LE, &ResultWriter::mk_predicted_},
      {"schedule/makespan/measured_ms", 0, 0, H5T_IEEE_F64LE, &ResultWriter::mk_measured_},
      {"schedule/makespan/bytes_moved", 0, 0, H5T_STD_U64LE, &ResultWriter::mk_bytes_},
      {"contact/active", 0, 0, H5T_STD_I32LE, &ResultWriter::contact_active_},
      {"contact/min_distance", 0, 0, H5T_IEEE_F64LE, &ResultWriter::contact_min_distance_},
      {"contact/max_penetration", 0, 0, H5T_IEEE_F64LE, &ResultWriter::contact_max_penetration_},
  };
  for (const Series& s : series) {
    if (create_them) {
      this->*s.member = create_series(file_, s.path, s.rows, s.cols, s.type);
    } else {
      this->*s.member = h5_check(H5Dopen2(file_, s.path, H5P_DEFAULT), H5Dclose, fmt::format("opening /{}", s.path));
    }
  }
  if (!create_them) {
    H5Handle space = h5_check(H5Dget_space(positions_), H5Sclose, "positions space");
    hsize_t dims[3] = {0, 0, 0};
    if (H5Sget_simple_extent_ndims(space) != 3 ||
        (H5Sget_simple_extent_dims(space, dims, nullptr), dims[1]) != particles_) {
      throw input_error(
          fmt::format("--resume: '{}' holds {} particles per frame, the scene has {}", writing_, dims[1], particles_));
    }
  }
}

ResultWriter::~ResultWriter() {
  if (!closed_ && broken_) abandon();
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

void ResultWriter::set_checkpoint(long long frame, std::span<const std::byte> positions,
                                  std::span<const std::byte> velocities) {
  Checkpoint c;
  c.frame = frame;
  c.positions.assign(positions.begin(), positions.end());
  c.velocities.assign(velocities.begin(), velocities.end());
  pending_ = std::move(c);
}

void ResultWriter::check_output_health(std::size_t frame_bytes) const {
  struct stat st {};
  if (::stat(writing_.c_str(), &st) != 0 || st.st_dev != device_ || st.st_ino != inode_) {
    throw runtime_error(
        fmt::format("the output file '{}' (or its folder) was removed or replaced during the run", writing_));
  }
  // Stop before the disk is full rather than in the middle of a flush: a
  // write that fails half-way can leave the metadata of the last good flush
  // pointing at space that was never written.
  struct statvfs fs {};
  const std::string folder = std::filesystem::path(writing_).has_parent_path()
                                 ? std::filesystem::path(writing_).parent_path().string()
                                 : std::string(".");
  if (::statvfs(folder.c_str(), &fs) == 0) {
    const unsigned long long free_bytes = static_cast<unsigned long long>(fs.f_bavail) * fs.f_frsize;
    const unsigned long long needed = 2ull * frame_bytes + (1ull << 20);
    if (free_bytes < needed) {
      throw runtime_error(fmt::format("the disk of '{}' is full ({} KiB free, a frame needs ~{} KiB with margin)",
                                      writing_, free_bytes / 1024, needed / 1024));
    }
  }
}

void ResultWriter::append_frame(double time, std::span<const float> xyz, double frame_ms, double schedule_ms,
                                const ContactFrame& contact) {
  if (xyz.size() != particles_ * 3) {
    throw std::logic_error(fmt::format("output: frame has {} values, expected {}", xyz.size(), particles_ * 3));
  }
  if (broken_) throw runtime_error(fmt::format("output '{}': an earlier write failed", writing_));
  const std::size_t state_bytes = pending_ ? pending_->positions.size() + pending_->velocities.size() : 0;
  check_output_health(xyz.size() * sizeof(float) + state_bytes);
  try {
    const hsize_t size[3] = {static_cast<hsize_t>(frames_ + 1), particles_, 3};
    h5_check(H5Dset_extent(positions_, size), "extending /frames/positions");
    H5Handle space = h5_check(H5Dget_space(positions_), H5Sclose, "positions space");
    const hsize_t start[3] = {static_cast<hsize_t>(frames_), 0, 0}, count[3] = {1, particles_, 3};
    h5_check(H5Sselect_hyperslab(space, H5S_SELECT_SET, start, nullptr, count, nullptr), "selecting a frame");
    H5Handle mem = h5_check(H5Screate_simple(3, count, nullptr), H5Sclose, "memory space");
    h5_check(H5Dwrite(positions_, H5T_NATIVE_FLOAT, mem, space, H5P_DEFAULT, xyz.data()), "writing positions");
    append_scalar(time_, time);
    append_scalar(frame_ms_, frame_ms);
    append_scalar(schedule_ms_, schedule_ms);
    const std::int32_t active[1] = {contact.active};
    append_rows<std::int32_t>(contact_active_, active, H5T_NATIVE_INT32, static_cast<hsize_t>(frames_));
    append_scalar(contact_min_distance_, contact.min_distance);
    append_scalar(contact_max_penetration_, contact.max_penetration);
    if (pending_) {
      pending_->frames_written = frames_ + 1;
      pending_->schedule_rows = static_cast<long long>(sched_rows_);
      pending_->wait_rows = static_cast<long long>(wait_rows_);
      pending_->makespan_rows = static_cast<long long>(makespan_rows_);
      if (!checkpoint_.valid()) {
        checkpoint_ = CheckpointSlots::create(file_, pending_->positions.size(), pending_->velocities.size());
      }
      checkpoint_.write(*pending_);
      pending_.reset();
    }
    h5_check(H5Fflush(file_, H5F_SCOPE_GLOBAL), "flushing the output file");
  } catch (...) {
    broken_ = true;
    throw;
  }
  ++frames_;
  times_.push_back(time);
  xdmf_.append(time);
}

void ResultWriter::finish() { close_with(true, ""); }
void ResultWriter::fail(const std::string& error) {
  if (broken_) {
    abandon();
    return;
  }
  try {
    close_with(false, error);
  } catch (const std::exception&) {
    abandon();  // the disk failed while recording the failure: keep the last flush
  }
}

// Lets go of every HDF5 identifier without closing: closing flushes, and a
// flush after a failed write could damage what the last good flush left.
// (main() calls H5dont_atexit(), so nothing is flushed at exit either.)
void ResultWriter::abandon() {
  closed_ = true;
  for (H5Handle* h :
       {&positions_,     &time_,          &frame_ms_,      &schedule_ms_,  &sched_frame_,   &sched_task_,
        &sched_device_,  &sched_pstart_,  &sched_pfinish_, &sched_mstart_, &sched_mfinish_, &wait_frame_,
        &wait_producer_, &wait_consumer_, &wait_pdevice_,  &wait_cdevice_, &mk_frame_,      &mk_predicted_,
        &mk_measured_,   &mk_bytes_,      &file_}) {
    (void)h->release();
  }
  checkpoint_ = CheckpointSlots();
  xdmf_.close();
}

void ResultWriter::close_with(bool complete, const std::string& error) {
  if (closed_) return;
  closed_ = true;
  xdmf_.close();
  checkpoint_ = CheckpointSlots();
  write_frame_views(file_, views_, static_cast<std::size_t>(frames_));
  write_int_attribute(file_, "complete", complete ? 1 : 0);
  write_string_attribute(file_, "error", error);
  for (H5Handle* h : {&positions_,
                      &time_,
                      &frame_ms_,
                      &schedule_ms_,
                      &sched_frame_,
                      &sched_task_,
                      &sched_device_,
                      &sched_pstart_,
                      &sched_pfinish_,
                      &sched_mstart_,
                      &sched_mfinish_,
                      &wait_frame_,
                      &wait_producer_,
                      &wait_consumer_,
                      &wait_pdevice_,
                      &wait_cdevice_,
                      &mk_frame_,
                      &mk_predicted_,
                      &mk_measured_,
                      &mk_bytes_,
                      &contact_active_,
                      &contact_min_distance_,
                      &contact_max_penetration_}) {
    h->reset();
  }
  h5_check(H5Fflush(file_, H5F_SCOPE_GLOBAL), "flushing the output file");
  file_.reset();
  write_xdmf_file(xdmf_path(), std::filesystem::path(writing_).filename().string(), views_, object_names_, times_);
  if (complete && writing_ != path_) {
    // The run that replaces an earlier result completed: only now does it take the path.
    const std::string partial_xdmf = xdmf_path();
    std::error_code ec;
    std::filesystem::rename(writing_, path_, ec);
    if (ec) throw runtime_error(fmt::format("cannot rename '{}' to '{}': {}", writing_, path_, ec.message()));
    writing_ = path_;
    write_xdmf_file(xdmf_path(), std::filesystem::path(writing_).filename().string(), views_, object_names_, times_);
    std::filesystem::remove(partial_xdmf, ec);
  }
}

std::string ResultWriter::xdmf_path() const {
  return std::filesystem::path(writing_).replace_extension(".xdmf").string();
}

}  // namespace atssim::io
