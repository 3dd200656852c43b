#pragma once
// `atssim converge`: the speed/accuracy trade of one substep (He et al. 2025
// Fig. 4). From one state (after some frames), each variant (method ×
// schedule × merge strategy) runs one substep with k iterations for several
// k; its result's incremental potential E_k is compared with the Newton
// minimum E*: y_k = (E_k − E*) / (E_0 − E*), E_0 = E(x~).
#include <string>
#include <vector>

#include "io/convergence_writer.hpp"

namespace atssim::app {

struct ConvergeOptions {
  std::string scene_path;
  std::vector<std::string> overrides;
  std::string command_line;
  std::vector<std::string> methods{"xpbd"};      // names of solver::methods()
  std::vector<std::string> schedules{"single"};  // single, split, heft, async
  std::vector<std::string> merges{"average_displacements", "average_positions", "main_precedence"};
  int max_iterations = 64;  // k = 1, 2, 4, …, max (and max itself)
  int frames_before = 10;   // simulated first (the scene's solver.method, one device) to reach a moving state
  int timing_repeats = 3;   // substeps timed per point; the median counts
  // A result file of `atssim run` (of this scene): the state is the one at
  // its newest checkpoint (the end of its last written frame) instead of
  // `frames_before` frames simulated here.
  std::string from;
};

// Throws atssim::Error (input) for unknown schedules or merges, a scene
// with infinitely stiff constraints (no finite energy), or too few devices.
io::ConvergenceResult run_convergence(const ConvergeOptions& options);

// "variant  k=1  k=2 …" table of y_k, one row per variant.
std::string format_convergence_table(const io::ConvergenceResult& result);

}  // namespace atssim::app
