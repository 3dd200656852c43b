#include "io/result_writer.hpp"

#include <algorithm>
#include <filesystem>
#include <limits>
#include <stdexcept>

#include <fmt/format.h>

#include "io/h5_errors.hpp"
#include "io/h5_series.hpp"
#include "io/output_health.hpp"
#include "io/reserve_driver.hpp"
#include "io/run_header.hpp"
#include "io/xdmf_writer.hpp"
#include "util/error.hpp"

namespace atssim::io {

namespace {

// Without HDF5's file locking: a reader (a notebook watching the run, or
// `atssim inspect`) may open the file while it is written; OutputLock keeps
// other writers out. Through the reserve driver, so that a kill during a
// flush leaves a file every reader opens (io/reserve_driver.hpp).
H5Handle file_access() {
  H5Handle fapl = h5_check(H5Pcreate(H5P_FILE_ACCESS), H5Pclose, "file access properties");
  h5_check(H5Pset_file_locking(fapl, false, true), "file locking");
  use_reserve_driver(fapl);
  return fapl;
}

// Chunk-index B-tree nodes of 2 x 256 entries instead of 2 x 32: a node
// split (new nodes written beside a parent rewritten in place) is the one
// change a torn flush can still leave unreadable, and a node this wide
// splits once per 512 chunks.
H5Handle file_creation() {
  H5Handle fcpl = h5_check(H5Pcreate(H5P_FILE_CREATE), H5Pclose, "file creation properties");
  h5_check(H5Pset_istore_k(fcpl, 256), "chunk index width");
  return fcpl;
}

// The file type of a series (a function: HDF5's type ids exist only once
// the library is open, after main() has started).
hid_t file_type(SeriesKind kind) {
  switch (kind) {
    case SeriesKind::f64:
      return H5T_IEEE_F64LE;
    case SeriesKind::f32:
      return H5T_IEEE_F32LE;
    case SeriesKind::i32:
      return H5T_STD_I32LE;
    case SeriesKind::u64:
      return H5T_STD_U64LE;
  }
  return H5T_IEEE_F64LE;
}

// /frames/flushed, [1] int64: created (a new file, or one written before it
// existed) or opened.
H5Handle open_flushed_record(hid_t file) {
  if (H5Lexists(file, "frames/flushed", H5P_DEFAULT) > 0) {
    return h5_check(H5Dopen2(file, "frames/flushed", H5P_DEFAULT), H5Dclose, "opening /frames/flushed");
  }
  const hsize_t one[1] = {1};
  H5Handle space = h5_check(H5Screate_simple(1, one, nullptr), H5Sclose, "flushed-frames space");
  return h5_check(H5Dcreate2(file, "frames/flushed", H5T_STD_I64LE, space, H5P_DEFAULT, H5P_DEFAULT, H5P_DEFAULT),
                  H5Dclose, "creating /frames/flushed");
}

// The frames /frames/flushed counts; a file written before it existed
// counts every row.
long long flushed_record(hid_t file) {
  if (H5Lexists(file, "frames/flushed", H5P_DEFAULT) <= 0) return std::numeric_limits<long long>::max();
  H5Handle set = h5_check(H5Dopen2(file, "frames/flushed", H5P_DEFAULT), H5Dclose, "opening /frames/flushed");
  long long n[1] = {0};
  h5_check(H5Dread(set, H5T_NATIVE_LLONG, H5S_ALL, H5S_ALL, H5P_DEFAULT, n), "reading /frames/flushed");
  return n[0];
}

}  // namespace

// Every per-frame series: its path, shape and file type.
const ResultWriter::SeriesSpec ResultWriter::kSeries[] = {
    {"frames/time", false, 0, SeriesKind::f64, &ResultWriter::time_},
    {"frames/positions", true, 3, SeriesKind::f32, &ResultWriter::positions_},
    {"timing/frame_ms", false, 0, SeriesKind::f64, &ResultWriter::frame_ms_},
    {"timing/schedule_ms", false, 0, SeriesKind::f64, &ResultWriter::schedule_ms_},
    {"timing/host_ms", false, 0, SeriesKind::f64, &ResultWriter::host_ms_},
    {"schedule/frame", false, 0, SeriesKind::i32, &ResultWriter::sched_frame_},
    {"schedule/task", false, 0, SeriesKind::i32, &ResultWriter::sched_task_},
    {"schedule/device", false, 0, SeriesKind::i32, &ResultWriter::sched_device_},
    {"schedule/predicted_start_ms", false, 0, SeriesKind::f64, &ResultWriter::sched_pstart_},
    {"schedule/predicted_finish_ms", false, 0, SeriesKind::f64, &ResultWriter::sched_pfinish_},
    {"schedule/measured_start_ms", false, 0, SeriesKind::f64, &ResultWriter::sched_mstart_},
    {"schedule/measured_finish_ms", false, 0, SeriesKind::f64, &ResultWriter::sched_mfinish_},
    {"schedule/merge_group", false, 0, SeriesKind::i32, &ResultWriter::sched_merge_},
    {"schedule/waits/frame", false, 0, SeriesKind::i32, &ResultWriter::wait_frame_},
    {"schedule/waits/producer", false, 0, SeriesKind::i32, &ResultWriter::wait_producer_},
    {"schedule/waits/consumer", false, 0, SeriesKind::i32, &ResultWriter::wait_consumer_},
    {"schedule/waits/producer_device", false, 0, SeriesKind::i32, &ResultWriter::wait_pdevice_},
    {"schedule/waits/consumer_device", false, 0, SeriesKind::i32, &ResultWriter::wait_cdevice_},
    {"schedule/makespan/frame", false, 0, SeriesKind::i32, &ResultWriter::mk_frame_},
    {"schedule/makespan/predicted_ms", false, 0, SeriesKind::f64, &ResultWriter::mk_predicted_},
    {"schedule/makespan/measured_ms", false, 0, SeriesKind::f64, &ResultWriter::mk_measured_},
    {"schedule/makespan/bytes_moved", false, 0, SeriesKind::u64, &ResultWriter::mk_bytes_},
    {"schedule/makespan/unmerged_predicted_ms", false, 0, SeriesKind::f64, &ResultWriter::mk_unmerged_},
    {"contact/active", false, 0, SeriesKind::i32, &ResultWriter::contact_active_},
    {"contact/min_distance", false, 0, SeriesKind::f64, &ResultWriter::contact_min_distance_},
    {"contact/max_penetration", false, 0, SeriesKind::f64, &ResultWriter::contact_max_penetration_},
    {"contact/surface_pairs", false, 0, SeriesKind::i32, &ResultWriter::surface_pairs_},
    {"contact/surface_max_penetration", false, 0, SeriesKind::f64, &ResultWriter::surface_max_penetration_},
    {"contact/surface_crossings", false, 0, SeriesKind::i32, &ResultWriter::surface_crossings_},
};

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
  opened_ = identify_output(writing_);
  xdmf_ = XdmfStream(xdmf_path(), std::filesystem::path(writing_).filename().string(), views_, object_names_, times_);
}

void ResultWriter::create(const RunInfo& info, std::span<const model::ObjectRange> objects) {
  std::error_code ec;
  writing_ = std::filesystem::exists(path_, ec) ? partial_path(path_) : path_;
  // The default (oldest) format bounds: a superblock without the
  // "open for writing" flags that would refuse readers after a kill.
  H5Handle fapl = file_access();
  H5Handle fcpl = file_creation();
  const hid_t id = H5Fcreate(writing_.c_str(), H5F_ACC_TRUNC, fcpl, fapl);
  if (id < 0) {
    throw runtime_error(
        fmt::format("cannot create output file '{}': {} (pass -o elsewhere)", writing_, hdf5_failure()));
  }
  file_ = H5Handle(id, H5Fclose);
  write_run_header(file_, info, objects);
  open_series(true);
  flushed_ = open_flushed_record(file_);
  views_ = write_xdmf_cells(file_, objects, particles_);
  flush();
  record_flushed_frames();
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
  // A kill inside a frame's flush can leave that frame's rows extended but
  // not yet written while its checkpoint is already whole (HDF5 writes the
  // parts of one flush in no set order): only the frames /frames/flushed
  // counts are known to be on disk in full.
  const long long available =
      std::min(static_cast<long long>(std::min(rows_of(positions_), rows_of(time_))), flushed_record(file_));
  std::optional<Checkpoint> point = slots ? slots->take_newest(available) : std::nullopt;
  if (!point) {
    throw input_error(
        fmt::format("--resume: '{}' holds no complete checkpoint (it was written by an atssim "
                    "without --resume, or killed before its first frame); run without --resume",
                    writing_));
  }
  checkpoint_ = std::move(*slots);
  frames_ = static_cast<int>(point->frames_written);
  for (hid_t set : {positions_.get(), time_.get(), frame_ms_.get(), schedule_ms_.get(), host_ms_.get(),
                    contact_active_.get(), contact_min_distance_.get(), contact_max_penetration_.get(),
                    surface_pairs_.get(), surface_max_penetration_.get(), surface_crossings_.get()})
    truncate_rows(set, frames_);
  read_contact_rows();
  if (H5Lexists(file_, "decisions", H5P_DEFAULT) > 0) decisions_ = DecisionSeries::open(file_, point->frame);
  sched_rows_ = static_cast<hsize_t>(point->schedule_rows);
  wait_rows_ = static_cast<hsize_t>(point->wait_rows);
  makespan_rows_ = static_cast<hsize_t>(point->makespan_rows);
  for (hid_t set : {sched_frame_.get(), sched_task_.get(), sched_device_.get(), sched_pstart_.get(),
                    sched_pfinish_.get(), sched_mstart_.get(), sched_mfinish_.get(), sched_merge_.get()})
    truncate_rows(set, sched_rows_);
  for (hid_t set :
       {wait_frame_.get(), wait_producer_.get(), wait_consumer_.get(), wait_pdevice_.get(), wait_cdevice_.get()})
    truncate_rows(set, wait_rows_);
  for (hid_t set : {mk_frame_.get(), mk_predicted_.get(), mk_measured_.get(), mk_bytes_.get(), mk_unmerged_.get()})
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
  flushed_ = open_flushed_record(file_);
  flush();
  record_flushed_frames();
  resume = std::move(*point);
}

// The series, created (a new file) or opened (a resumed one).
void ResultWriter::open_series(bool create_them) {
  for (const SeriesSpec& s : kSeries) {
    if (create_them) {
      this->*s.member = create_series(file_, s.path, s.per_particle ? particles_ : 0, s.cols, file_type(s.kind));
    } else {
      if (H5Lexists(file_, s.path, H5P_DEFAULT) <= 0) {
        throw input_error(fmt::format(
            "--resume: '{}' has no /{} (it was written by an older atssim); run without --resume", writing_, s.path));
      }
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

// The first frames_ rows of the /contact series, for the run's summary.
void ResultWriter::read_contact_rows() {
  const auto rows = [&](hid_t set) {
    std::vector<double> v(static_cast<std::size_t>(frames_));
    if (frames_ == 0) return v;
    H5Handle file_space = h5_check(H5Dget_space(set), H5Sclose, "contact space");
    const hsize_t start[1] = {0}, count[1] = {static_cast<hsize_t>(frames_)};
    h5_check(H5Sselect_hyperslab(file_space, H5S_SELECT_SET, start, nullptr, count, nullptr), "selecting rows");
    H5Handle mem = h5_check(H5Screate_simple(1, count, nullptr), H5Sclose, "memory space");
    h5_check(H5Dread(set, H5T_NATIVE_DOUBLE, mem, file_space, H5P_DEFAULT, v.data()), "reading /contact");
    return v;
  };
  const std::vector<double> active = rows(contact_active_), min_distance = rows(contact_min_distance_),
                            depth = rows(contact_max_penetration_), pairs = rows(surface_pairs_),
                            surface_depth = rows(surface_max_penetration_), crossings = rows(surface_crossings_);
  resumed_contact_.resize(static_cast<std::size_t>(frames_));
  for (std::size_t f = 0; f < resumed_contact_.size(); ++f) {
    resumed_contact_[f] = {static_cast<int>(active[f]), min_distance[f],  depth[f],
                           static_cast<int>(pairs[f]),  surface_depth[f], static_cast<int>(crossings[f])};
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
  append_series_rows<double>(set, one, H5T_NATIVE_DOUBLE, static_cast<hsize_t>(frames_));
}

void ResultWriter::append_schedule(int frame, std::span<const ScheduledTask> tasks, std::span<const sched::Wait> waits,
                                   double predicted_makespan_ms, double measured_makespan_ms, std::size_t bytes_moved,
                                   double unmerged_makespan_ms) {
  std::vector<int> f(tasks.size(), frame), task, device, merge;
  std::vector<double> ps, pf, ms, mf;
  for (const ScheduledTask& t : tasks) {
    task.push_back(static_cast<int>(t.task));
    device.push_back(t.device);
    merge.push_back(t.merge_group);
    ps.push_back(t.predicted_start_ms);
    pf.push_back(t.predicted_finish_ms);
    ms.push_back(t.measured_start_ms);
    mf.push_back(t.measured_finish_ms);
  }
  hsize_t rows = sched_rows_;
  append_series_rows<int>(sched_frame_, f, H5T_NATIVE_INT, rows);
  append_series_rows<int>(sched_task_, task, H5T_NATIVE_INT, rows);
  append_series_rows<int>(sched_device_, device, H5T_NATIVE_INT, rows);
  append_series_rows<double>(sched_pstart_, ps, H5T_NATIVE_DOUBLE, rows);
  append_series_rows<double>(sched_pfinish_, pf, H5T_NATIVE_DOUBLE, rows);
  append_series_rows<double>(sched_mstart_, ms, H5T_NATIVE_DOUBLE, rows);
  append_series_rows<double>(sched_mfinish_, mf, H5T_NATIVE_DOUBLE, rows);
  append_series_rows<int>(sched_merge_, merge, H5T_NATIVE_INT, rows);
  sched_rows_ += tasks.size();

  std::vector<int> wf(waits.size(), frame), producer, consumer, pdev, cdev;
  for (const sched::Wait& w : waits) {
    producer.push_back(static_cast<int>(w.producer));
    consumer.push_back(static_cast<int>(w.consumer));
    pdev.push_back(static_cast<int>(w.producer_device));
    cdev.push_back(static_cast<int>(w.consumer_device));
  }
  rows = wait_rows_;
  append_series_rows<int>(wait_frame_, wf, H5T_NATIVE_INT, rows);
  append_series_rows<int>(wait_producer_, producer, H5T_NATIVE_INT, rows);
  append_series_rows<int>(wait_consumer_, consumer, H5T_NATIVE_INT, rows);
  append_series_rows<int>(wait_pdevice_, pdev, H5T_NATIVE_INT, rows);
  append_series_rows<int>(wait_cdevice_, cdev, H5T_NATIVE_INT, rows);
  wait_rows_ += waits.size();

  rows = makespan_rows_;
  const int fr[1] = {frame};
  const double p[1] = {predicted_makespan_ms}, m[1] = {measured_makespan_ms};
  append_series_rows<int>(mk_frame_, fr, H5T_NATIVE_INT, rows);
  append_series_rows<double>(mk_predicted_, p, H5T_NATIVE_DOUBLE, rows);
  append_series_rows<double>(mk_measured_, m, H5T_NATIVE_DOUBLE, rows);
  const std::uint64_t b[1] = {bytes_moved};
  append_series_rows<std::uint64_t>(mk_bytes_, b, H5T_NATIVE_UINT64, rows);
  const double u[1] = {unmerged_makespan_ms};
  append_series_rows<double>(mk_unmerged_, u, H5T_NATIVE_DOUBLE, rows);
  makespan_rows_ += 1;
}

void ResultWriter::append_decision(const DecisionRecord& row) {
  if (broken_) return;
  if (!decisions_.valid()) decisions_ = DecisionSeries::create(file_);
  decisions_.append(row);
}

void ResultWriter::set_decision_measured(double measured_ms) {
  if (!broken_ && decisions_.valid()) decisions_.set_last_measured(measured_ms);
}

const std::vector<DecisionRecord>& ResultWriter::decisions() const { return decisions_.records(); }

void ResultWriter::set_checkpoint(long long frame, std::span<const std::byte> positions,
                                  std::span<const std::byte> velocities, std::span<const std::byte> carried) {
  // Copied into the storage of the last one (of the same sizes), so that a
  // large carried state costs a copy a frame, not fresh pages.
  Checkpoint& c = pending_;
  c.frame = frame;
  c.positions.assign(positions.begin(), positions.end());
  c.velocities.assign(velocities.begin(), velocities.end());
  c.carried.assign(carried.begin(), carried.end());
  checkpoint_due_ = true;
}

void ResultWriter::append_frame(double time, std::span<const float> xyz, double frame_ms, double schedule_ms,
                                const ContactFrame& contact, double host_ms) {
  if (xyz.size() != particles_ * 3) {
    throw std::logic_error(fmt::format("output: frame has {} values, expected {}", xyz.size(), particles_ * 3));
  }
  if (broken_) throw runtime_error(fmt::format("output '{}': an earlier write failed", writing_));
  const std::size_t state_bytes =
      checkpoint_due_ ? pending_.positions.size() + pending_.velocities.size() + pending_.carried.size() : 0;
  check_output_health(writing_, opened_, xyz.size() * sizeof(float) + state_bytes);
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
    append_scalar(host_ms_, host_ms);
    const std::int32_t active[1] = {contact.active};
    append_series_rows<std::int32_t>(contact_active_, active, H5T_NATIVE_INT32, static_cast<hsize_t>(frames_));
    append_scalar(contact_min_distance_, contact.min_distance);
    append_scalar(contact_max_penetration_, contact.max_penetration);
    const std::int32_t pairs[1] = {contact.surface_pairs}, crossings[1] = {contact.surface_crossings};
    append_series_rows<std::int32_t>(surface_pairs_, pairs, H5T_NATIVE_INT32, static_cast<hsize_t>(frames_));
    append_scalar(surface_max_penetration_, contact.surface_max_penetration);
    append_series_rows<std::int32_t>(surface_crossings_, crossings, H5T_NATIVE_INT32, static_cast<hsize_t>(frames_));
    if (checkpoint_due_) {
      pending_.frames_written = frames_ + 1;
      pending_.schedule_rows = static_cast<long long>(sched_rows_);
      pending_.wait_rows = static_cast<long long>(wait_rows_);
      pending_.makespan_rows = static_cast<long long>(makespan_rows_);
      // (A file resumed from an atssim that kept no carried state goes on without it.)
      if (checkpoint_.valid() && checkpoint_.carried_bytes() == 0) pending_.carried.clear();
      if (!checkpoint_.valid()) {
        checkpoint_ = CheckpointSlots::create(file_, pending_.positions.size(), pending_.velocities.size(),
                                              pending_.carried.size());
      }
      checkpoint_.write(pending_);
      checkpoint_due_ = false;
    }
    flush();
    ++frames_;
    record_flushed_frames();
  } catch (...) {
    broken_ = true;
    throw;
  }
  times_.push_back(time);
  xdmf_.append(time);
}

// Every flush of the output: the reserve covers two frames of positions and
// a checkpoint (positions, velocities, multipliers) with a MiB to spare.
void ResultWriter::flush() {
  prepare_flush(file_, (1u << 20) + 96 * particles_);
  h5_check(H5Fflush(file_, H5F_SCOPE_GLOBAL), "flushing the output file");
}

// Written only after the flush that put every row of those frames on disk,
// and flushed at once: a reader that reads rows below /frames/flushed never
// reads into a flush (the rows above may be half-written).
void ResultWriter::record_flushed_frames() {
  const long long n[1] = {frames_};
  h5_check(H5Dwrite(flushed_, H5T_NATIVE_LLONG, H5S_ALL, H5S_ALL, H5P_DEFAULT, n), "writing /frames/flushed");
  h5_check(H5Fflush(file_, H5F_SCOPE_GLOBAL), "flushing the output file");
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
  for (const SeriesSpec& s : kSeries) (void)(this->*s.member).release();
  (void)flushed_.release();
  decisions_.close(true);
  (void)file_.release();
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
  for (const SeriesSpec& s : kSeries) (this->*s.member).reset();
  flushed_.reset();
  decisions_.close();
  flush();
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
