#pragma once
// Writes a run to HDF5 (format v1, docs/output-format.md) as it goes: every
// frame is appended and flushed, under HDF5's single-writer/multi-reader
// mode, so a run that is killed leaves a readable file holding every frame
// flushed before the kill. The root attribute `complete` turns 1 only when
// the run ended well; a failed run records its `error`.
#include <limits>
#include <span>
#include <string>
#include <vector>

#include "io/h5_handle.hpp"
#include "io/xdmf_views.hpp"
#include "model/model.hpp"
#include "sched/cost_table.hpp"
#include "sched/schedule.hpp"

namespace atssim::io {

constexpr int kFormatVersion = 1;

// A device as the output describes it (plain data: the writer links no OpenCL).
struct DeviceRecord {
  std::string name, vendor, type, platform, version;
  std::string svm;  // e.g. "coarse+fine+atomics"
  int compute_units = 0;
  int index = -1;  // in `atssim devices`
  int sub_device = -1;
};

// One task of the substep plan.
struct TaskRecord {
  std::string name;
  std::string kind;  // "predict", "stretch", … (plan::TaskKind)
  int iteration = -1;
  int block = -1;
  int part = -1;
};

// The substep's tasks and what the scheduler was given.
struct ScheduleInfo {
  std::string mode;               // "single", "split", "heft", "async"
  std::string executor;           // "events" or "fused"
  std::string memory = "shared";  // "shared" (SVM within a platform) or "separate" (copies between memories)
  std::vector<TaskRecord> tasks;
  std::vector<std::pair<int, int>> edges;
  sched::CostTable costs;               // pre-profiled, ms, task × device
  std::vector<double> latency_ms;       // device × device hop latency
  std::vector<double> ms_per_byte;      // device × device copy cost per byte (separate memories; empty if shared)
  std::vector<double> split_fractions;  // share of each device ("split")
};

struct RunInfo {
  std::string command_line;
  std::string scene_yaml;     // as given
  std::string resolved_yaml;  // after defaults and --set
  std::vector<DeviceRecord> devices;
  ScheduleInfo schedule;
};

// One task of the substep recorded in a frame: where it ran, when the
// scheduler predicted it, when it ran (ms from the substep's first start).
struct ScheduledTask {
  sched::TaskId task = 0;
  int device = 0;
  double predicted_start_ms = 0, predicted_finish_ms = 0;
  double measured_start_ms = 0, measured_finish_ms = 0;
};

// The particles' contact with the colliders in one frame (docs/output-format.md
// /contact): touching particle-collider pairs, the smallest gap (distance
// to a surface less its thickness; NaN without colliders) and the largest
// penetration into a thickened surface (0 when none).
struct ContactFrame {
  int active = 0;
  double min_distance = std::numeric_limits<double>::quiet_NaN();
  double max_penetration = 0.0;
};

class ResultWriter {
 public:
  // Creates (truncates) `path` and writes everything but the frames;
  // `objects` are the simulated objects' particle ranges and topology.
  ResultWriter(const std::string& path, const RunInfo& info, std::span<const model::ObjectRange> objects);
  ResultWriter(const ResultWriter&) = delete;
  ResultWriter& operator=(const ResultWriter&) = delete;
  ~ResultWriter();

  // Appends one frame (xyz per particle) and flushes it to disk.
  void append_frame(double time, std::span<const float> xyz, double frame_ms, double schedule_ms = 0.0,
                    const ContactFrame& contact = {});
  // Appends the recorded substep of simulated frame `frame` (written with
  // the next append_frame's flush).
  void append_schedule(int frame, std::span<const ScheduledTask> tasks, std::span<const sched::Wait> waits,
                       double predicted_makespan_ms, double measured_makespan_ms, std::size_t bytes_moved = 0);
  int frames_written() const { return frames_; }

  // Closes the file, marking it complete, or failed with `error`.
  void finish();
  void fail(const std::string& error);

  const std::string& path() const { return path_; }
  std::string xdmf_path() const;

 private:
  void close_with(bool complete, const std::string& error);
  void write_xdmf() const;
  void append_scalar(hid_t set, double value);
  template <typename T>
  void append_rows(hid_t set, std::span<const T> values, hid_t mem_type, hsize_t rows);

  std::string path_;
  std::vector<std::string> object_names_;  // for the XDMF sidecar
  XdmfViews views_;
  std::size_t particles_ = 0;
  int frames_ = 0;
  std::vector<double> times_;
  bool closed_ = false;
  H5Handle file_, positions_, time_, frame_ms_, schedule_ms_;
  // /schedule series: one row per recorded task, per wait, per frame.
  H5Handle sched_frame_, sched_task_, sched_device_, sched_pstart_, sched_pfinish_, sched_mstart_, sched_mfinish_;
  H5Handle wait_frame_, wait_producer_, wait_consumer_, wait_pdevice_, wait_cdevice_;
  H5Handle mk_frame_, mk_predicted_, mk_measured_, mk_bytes_;
  H5Handle contact_active_, contact_min_distance_, contact_max_penetration_;  // /contact, per frame
  hsize_t sched_rows_ = 0, wait_rows_ = 0, makespan_rows_ = 0;
};

}  // namespace atssim::io
