#pragma once
// Writes a run to HDF5 (format v1, docs/output-format.md) as it goes: every
// frame is appended and flushed, so a run that is killed leaves a file that
// a plain `h5py.File(path, "r")` opens, holding every frame flushed before
// the kill (no SWMR: a SWMR writer leaves flags that refuse plain readers).
// The root attribute `complete` turns 1 only when the run ended well; a
// failed run records its `error`. One writer per path (io/output_lock.hpp);
// when a file is already at the path, the run writes "<stem>.partial<ext>"
// and renames it over the path only when it completes, so a failing run
// never destroys an earlier result.
#include <limits>
#include <memory>
#include <optional>
#include <span>
#include <string>
#include <vector>

#include "io/checkpoint.hpp"
#include "io/decision_series.hpp"
#include "io/h5_handle.hpp"
#include "io/output_health.hpp"
#include "io/output_lock.hpp"
#include "io/run_header.hpp"
#include "io/run_info.hpp"
#include "io/xdmf_views.hpp"
#include "io/xdmf_writer.hpp"
#include "model/model.hpp"
#include "sched/schedule.hpp"

namespace atssim::io {

enum class SeriesKind { f64, f32, i32, u64 };  // a series' element type in the file

// One task of the substep recorded in a frame: where it ran, when the
// scheduler predicted it, when it ran (ms from the substep's first start).
struct ScheduledTask {
  sched::TaskId task = 0;
  int device = 0;
  double predicted_start_ms = 0, predicted_finish_ms = 0;
  double measured_start_ms = 0, measured_finish_ms = 0;
  int merge_group = -1;  // heft: the merged task it ran in (sched/merged_heft.hpp); -1 alone
};

// The particles' contact with the colliders in one frame (docs/output-format.md
// /contact): touching particle-collider pairs, the smallest gap (distance
// to a surface less its thickness; NaN without colliders) and the largest
// penetration into a thickened surface (0 when none).
// Between the simulated surfaces (a scene with `contact: {self: true}`;
// -1, NaN, -1 without one): non-incident vertex-triangle and edge-edge
// pairs closer than the contact thickness, the thickness less the smallest
// of their distances (0 when none), and the edge-triangle pairs where a
// surface edge passes through a triangle it does not touch.
struct ContactFrame {
  int active = 0;
  double min_distance = std::numeric_limits<double>::quiet_NaN();
  double max_penetration = 0.0;
  int surface_pairs = -1;
  double surface_max_penetration = std::numeric_limits<double>::quiet_NaN();
  int surface_crossings = -1;
};

class ResultWriter {
 public:
  // Creates the output for `path` and writes everything but the frames;
  // `objects` are the simulated objects' particle ranges and topology.
  // With `resume`, reopens instead the file a killed or stopped run left
  // for `path` (its partial file first), drops what came after its newest
  // checkpoint and fills `*resume` with it; the run goes on from there.
  // Throws atssim::Error: input when the path cannot be written, is locked
  // by another run, or (resume) holds no resumable run of this scene.
  ResultWriter(const std::string& path, const RunInfo& info, std::span<const model::ObjectRange> objects,
               Checkpoint* resume = nullptr);
  ResultWriter(const ResultWriter&) = delete;
  ResultWriter& operator=(const ResultWriter&) = delete;
  ~ResultWriter();

  // Appends one frame (xyz per particle) and its contact record, and
  // flushes it to disk, with the state set by set_checkpoint() since the last
  // frame. Before writing it checks that the output is still there and that
  // the disk has room for the frame; a failed write leaves the file as the
  // last flush made it.
  // frame_ms, schedule_ms, host_ms: /timing (docs/output-format.md).
  void append_frame(double time, std::span<const float> xyz, double frame_ms, double schedule_ms = 0.0,
                    const ContactFrame& contact = {}, double host_ms = 0.0);
  // The executor's state at the end of simulated frame `frame`, stored with
  // the next append_frame (for --resume); `carried`: what its plan carries
  // besides (plan::PlanState, the contact lists' state).
  void set_checkpoint(long long frame, std::span<const std::byte> positions, std::span<const std::byte> velocities,
                      std::span<const std::byte> carried = {});
  // Appends the recorded substep of simulated frame `frame` (written with
  // the next append_frame's flush).
  void append_schedule(int frame, std::span<const ScheduledTask> tasks, std::span<const sched::Wait> waits,
                       double predicted_makespan_ms, double measured_makespan_ms, std::size_t bytes_moved = 0,
                       double unmerged_makespan_ms = std::numeric_limits<double>::quiet_NaN());
  // One row of /decisions (run --tolerance / --budget), written with the
  // next flush; the first call makes the group. set_decision_measured()
  // writes the last row's measured frame time again.
  void append_decision(const DecisionRecord& row);
  void set_decision_measured(double measured_ms);
  // The rows of /decisions, those a resumed run kept included.
  const std::vector<DecisionRecord>& decisions() const;
  int frames_written() const { return frames_; }
  // After a resume: the contact record of every frame kept in the file.
  const std::vector<ContactFrame>& resumed_contact() const { return resumed_contact_; }

  // Closes the file, marking it complete, or failed with `error`.
  void finish();
  void fail(const std::string& error);

  // Where the frames are now (the partial file until a replacing run completes).
  const std::string& path() const { return writing_; }
  // The path asked for.
  const std::string& target_path() const { return path_; }
  std::string xdmf_path() const;

 private:
  void create(const RunInfo& info, std::span<const model::ObjectRange> objects);
  void reopen(const RunInfo& info, Checkpoint& resume);
  void open_series(bool create_them);
  void close_with(bool complete, const std::string& error);
  void abandon();
  void append_scalar(hid_t set, double value);
  void read_contact_rows();
  void flush();
  void record_flushed_frames();

  struct SeriesSpec {
    const char* path;
    bool per_particle;  // [F, particles, cols] rather than [F]
    std::size_t cols;
    SeriesKind kind;
    H5Handle ResultWriter::*member;
  };
  static const SeriesSpec kSeries[];

  std::unique_ptr<OutputLock> lock_;
  std::string path_, writing_;
  OutputIdentity opened_;  // writing_, to notice it vanish
  bool broken_ = false;    // an HDF5 write failed: write nothing more
  Checkpoint pending_;     // the state set_checkpoint gave, written with the next frame
  bool checkpoint_due_ = false;
  CheckpointSlots checkpoint_;
  XdmfStream xdmf_;
  std::vector<std::string> object_names_;  // for the XDMF sidecar
  XdmfViews views_;
  std::size_t particles_ = 0;
  int frames_ = 0;
  std::vector<double> times_;
  bool closed_ = false;
  H5Handle file_, positions_, time_, frame_ms_, schedule_ms_, host_ms_;
  H5Handle flushed_;  // /frames/flushed: frames written and flushed in full (live readers read those)
  // /schedule series: one row per recorded task, per wait, per frame.
  H5Handle sched_frame_, sched_task_, sched_device_, sched_pstart_, sched_pfinish_, sched_mstart_, sched_mfinish_;
  H5Handle sched_merge_;
  H5Handle wait_frame_, wait_producer_, wait_consumer_, wait_pdevice_, wait_cdevice_;
  H5Handle mk_frame_, mk_predicted_, mk_measured_, mk_bytes_, mk_unmerged_;
  H5Handle contact_active_, contact_min_distance_, contact_max_penetration_;  // /contact, per frame
  H5Handle surface_pairs_, surface_max_penetration_, surface_crossings_;
  std::vector<ContactFrame> resumed_contact_;
  DecisionSeries decisions_;
  hsize_t sched_rows_ = 0, wait_rows_ = 0, makespan_rows_ = 0;
};

}  // namespace atssim::io
