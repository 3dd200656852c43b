#pragma once
// Wires the pipeline for `atssim run`: scene -> model -> the method's plan
// -> devices -> frames -> HDF5 (with a tolerance or a budget, the probe's
// choice first: app/accuracy_control).
#include <cmath>
#include <functional>
#include <span>
#include <string>
#include <vector>

#include "io/result_writer.hpp"

namespace atssim::app {

struct RunOptions {
  std::string scene_path;
  std::vector<std::string> overrides;  // --set key=value, plus -o/--frames/--devices turned into overrides
  std::string command_line;
  // Forced coarse-grain SVM (tests exercise both paths); empty = automatic.
  std::string svm_mode;
  // Continue the run a killed or stopped run left at the output path from
  // its last checkpoint (the same positions as an uninterrupted run).
  bool resume = false;
  // Called with a warning's text (no prefix, no newline), e.g. that surfaces
  // crossed; unset: printed on stderr as "atssim: warning: TEXT".
  std::function<void(const std::string&)> warn;
  // A tolerance or a budget: the cost model's ms per µs of the reference
  // device instead of a profile (tests decide a budget without timings); 0 = profile.
  double cost_scale = 0.0;
};

struct RunProgress {
  int frame = 0;        // frames simulated so far
  int frames = 0;       // frames asked for
  double frame_ms = 0;  // wall time of the last frame
  double mean_ms = 0;   // mean so far
};

struct RunResult {
  std::string output_path;
  std::string xdmf_path;
  int frames_requested = 0;
  int frames_simulated = 0;
  int frames_written = 0;  // including the initial state
  double mean_frame_ms = 0;
  std::size_t particles = 0;
  std::string device;  // the first device's name
  // What `run --json` reports (docs/run-json.md).
  std::string method, schedule, executor;
  std::string memory;  // "shared" or "separate" (whether the devices had more than one memory)
  std::vector<io::DeviceRecord> devices;
  std::vector<double> frame_ms;  // wall time of every simulated frame
  std::vector<double> host_ms;   // the host's own work on every written frame (/timing/host_ms)
  // Per recorded frame: the substep makespan the scheduler predicted and the
  // one measured (ms).
  std::vector<double> predicted_makespan_ms, measured_makespan_ms;
  std::vector<double> bytes_moved;  // per simulated frame: bytes copied between memories
  // Per written frame (resumed ones included): its simulated frame and its
  // /contact record; the surface figures are measured only when the scene
  // has a contact surface (`contact: {self: true}`).
  struct ContactRecord {
    int frame = 0;
    io::ContactFrame values;
  };
  bool surface_contact = false;
  std::vector<ContactRecord> contact;
  // The largest growth of kinetic + elastic energy over one frame, relative
  // to what the energy check allows for (app/energy_growth.hpp); the run
  // fails above simulation.energy_growth_limit.
  double energy_growth = -INFINITY;

  // run --tolerance / --budget (docs/accuracy.md): what was asked, and every
  // choice made (the rows of /decisions, those a resumed run kept included).
  bool tuned = false;
  double tolerance = 0.0, budget_ms = 0.0;
  int recheck = 0;
  std::vector<io::DecisionRecord> decisions;
};

// Throws atssim::Error: input errors before anything is written; runtime
// errors after the output file exists carry "N frames kept in FILE".
RunResult run_simulation(const RunOptions& options, const std::function<void(const RunProgress&)>& progress = {});
// The same, filling `result` as the run goes, so that a caller that catches
// the error still has what was done and measured.
void run_simulation(const RunOptions& options, RunResult& result,
                    const std::function<void(const RunProgress&)>& progress = {});

}  // namespace atssim::app
namespace atssim::scene {
struct SceneDesc;
}  // namespace atssim::scene
namespace atssim::plan {
struct SubstepPlan;
}
namespace atssim::app {
// A scene file as `run`, `schedule` and `converge` read it: loaded and
// validated, its method (solver.method) and that method's options checked
// against the method registry, the options' defaults filled in and the
// resolved YAML written again with them.
scene::SceneDesc load_scene(const std::string& path, std::span<const std::string> overrides);

// The substep plan of a validated scene (model -> layout -> solver plan).
plan::SubstepPlan substep_plan_for(const scene::SceneDesc& scene);

// Set from a signal handler: the run stops before the next substep, keeps
// the frames it wrote and fails with "interrupted".
void request_stop();
bool stop_requested();

}  // namespace atssim::app
