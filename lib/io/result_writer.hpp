#pragma once
// Writes a run to HDF5 (format v1, docs/output-format.md) as it goes: every
// frame is appended and flushed, under HDF5's single-writer/multi-reader
// mode, so a run that is killed leaves a readable file holding every frame
// flushed before the kill. The root attribute `complete` turns 1 only when
// the run ended well; a failed run records its `error`.
#include <span>
#include <string>
#include <vector>

#include "device/device_info.hpp"
#include "io/h5_handle.hpp"
#include "model/model.hpp"

namespace atssim::io {

constexpr int kFormatVersion = 1;

struct RunInfo {
  std::string command_line;
  std::string scene_yaml;      // as given
  std::string resolved_yaml;   // after defaults and --set
  std::vector<device::DeviceInfo> devices;
};

class ResultWriter {
 public:
  // Creates (truncates) `path` and writes everything but the frames.
  ResultWriter(const std::string& path, const RunInfo& info, const model::Model& model);
  ResultWriter(const ResultWriter&) = delete;
  ResultWriter& operator=(const ResultWriter&) = delete;
  ~ResultWriter();

  // Appends one frame (xyz per particle) and flushes it to disk.
  void append_frame(double time, std::span<const float> xyz, double frame_ms);
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

  std::string path_;
  std::vector<model::ObjectRange> objects_;  // topology for the XDMF sidecar
  std::size_t particles_ = 0;
  int frames_ = 0;
  std::vector<double> times_;
  bool closed_ = false;
  H5Handle file_, positions_, time_, frame_ms_;
};

}  // namespace atssim::io
