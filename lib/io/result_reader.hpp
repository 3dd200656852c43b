#pragma once
// Reads back what ResultWriter wrote (for `atssim inspect` and tests).
#include <string>
#include <vector>

#include "io/checkpoint.hpp"
#include "io/decision_series.hpp"

namespace atssim::io {

struct ResultSummary {
  std::string format;
  long long format_version = 0;
  std::string atssim_version;
  std::string command_line;
  std::string created;
  bool complete = false;
  std::string error;
  std::size_t frames = 0;
  std::size_t particles = 0;
  std::vector<std::string> objects;
  std::vector<std::string> devices;
  std::vector<double> time;
  std::vector<double> frame_ms;
};

// Throws atssim::Error (input) when the file is missing or not an atssim file.
ResultSummary read_summary(const std::string& path);
// Positions of one frame, xyz per particle.
std::vector<float> read_frame_positions(const std::string& path, std::size_t frame);
// A 1-D series as doubles, e.g. "/contact/max_penetration".
std::vector<double> read_series(const std::string& path, const std::string& dataset);
// The newest whole checkpoint (the state at the end of that frame); throws
// atssim::Error (input) when the file has none.
Checkpoint read_checkpoint(const std::string& path);
// The rows of /decisions (run --tolerance / --budget); empty without.
std::vector<DecisionRecord> read_decisions(const std::string& path);

}  // namespace atssim::io
