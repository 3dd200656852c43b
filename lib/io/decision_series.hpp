#pragma once
// /decisions of a result file (docs/output-format.md): one row per choice
// of `run --tolerance` / `--budget` — the probe before frame 1 and every
// re-check — with the error measured, the choice, and its predicted and
// measured frame time. Extendible series like the per-frame ones; a row's
// measured time is known only once the frames it chose have run, so it is
// written again then (NaN until).
#include <limits>
#include <string>
#include <vector>

#include "io/h5_handle.hpp"

namespace atssim::io {

struct DecisionRecord {
  int frame = 0;  // the choice holds from the frame after this one (0: before frame 1)
  std::string method;
  int iterations = 0;
  std::string schedule;
  double y = std::numeric_limits<double>::quiet_NaN();             // of the choice, on this frame's state
  double previous_y = std::numeric_limits<double>::quiet_NaN();    // of the choice before (NaN at the probe)
  double y_floor = std::numeric_limits<double>::quiet_NaN();       // float32 resolution of y on that state
  double predicted_ms = std::numeric_limits<double>::quiet_NaN();  // per frame, cost model
  double measured_ms = std::numeric_limits<double>::quiet_NaN();   // median wall time of its frames
  double check_ms = std::numeric_limits<double>::quiet_NaN();      // wall time the probe or re-check took
  int changed = 0;     // 1 when the method, iterations or schedule differ from the row before
  std::string reason;  // one line: why (probe, y above the tolerance, budget feedback, kept)
};

class DecisionSeries {
 public:
  DecisionSeries() = default;
  // Creates /decisions in `file`; or, for a resumed run, opens the one
  // there keeping only its rows up to frame `keep_through` (the choices in
  // force at the checkpoint), or creates it when the file has none.
  static DecisionSeries create(hid_t file);
  static DecisionSeries open(hid_t file, long long keep_through);

  bool valid() const { return frame_.get() >= 0; }
  std::size_t rows() const { return rows_.size(); }
  const std::vector<DecisionRecord>& records() const { return rows_; }

  void append(const DecisionRecord& row);
  // The last row's measured frame time.
  void set_last_measured(double measured_ms);
  // Closes the datasets, or lets go of them without closing (a file whose
  // writes failed: ResultWriter::abandon).
  void close(bool abandon = false);

 private:
  void write_row(std::size_t index, bool extend);

  struct Column {
    const char* name;
    H5Handle DecisionSeries::*member;
  };
  static const Column kColumns[];

  H5Handle frame_, method_, iterations_, schedule_, y_, previous_y_, y_floor_, predicted_, measured_, check_, changed_,
      reason_;
  std::vector<DecisionRecord> rows_;
};

// The rows of /decisions in a file written before (empty when it has none).
std::vector<DecisionRecord> read_decisions(hid_t file);

}  // namespace atssim::io
