#pragma once
// Running a scene written by a test through the app (app::run_simulation)
// and reading its frames back: the set-up the app-level tests share.
#include <string>
#include <vector>

#include <Eigen/Core>

#include "app/convergence.hpp"
#include "app/simulation.hpp"
#include "io/result_reader.hpp"
#include "support/temp_dir.hpp"

namespace atssim::test {

// Run options for `yaml` written into `dir`: the output `output` there, the
// two 1-CU sub-devices, `method` and `schedule`.
inline app::RunOptions options(const TempDir& dir, const std::string& yaml, const std::string& method,
                               const std::string& schedule, const std::string& output = "out.h5") {
  app::RunOptions o;
  o.scene_path = dir.write("scene.yaml", yaml);
  o.overrides = {"output.path=" + dir.file(output), "devices=cpu/2", "solver.method=" + method,
                 "solver.schedule=" + schedule};
  return o;
}

// `atssim converge` of VBD, JPGD and SOSD (in that order) on `yaml` written
// into `dir`, 20 frames in, on the whole CPU device, up to `max_iterations`.
inline app::ConvergeOptions converge_options(const TempDir& dir, const std::string& yaml, int max_iterations) {
  app::ConvergeOptions o;
  o.scene_path = dir.write("rest.yaml", yaml);
  o.overrides = {"devices=cpu"};
  o.methods = {"vbd", "jpgd", "sosd"};
  o.max_iterations = max_iterations;
  o.frames_before = 20;
  o.timing_repeats = 1;
  return o;
}

// Frame f of a result file as points.
inline std::vector<Eigen::Vector3d> frame(const std::string& file, std::size_t f) {
  const std::vector<float> xyz = io::read_frame_positions(file, f);
  std::vector<Eigen::Vector3d> out;
  for (std::size_t i = 0; i + 2 < xyz.size(); i += 3) out.emplace_back(xyz[i], xyz[i + 1], xyz[i + 2]);
  return out;
}

}  // namespace atssim::test
