// `run --tolerance` / `--budget` end to end (docs/accuracy.md, "Accuracy as
// the input"): on small versions of the three bundled scenes, every choice
// a re-check keeps or makes is measured again by `converge` from the state
// a run of that length ends at; the run's decisions repeat; a tighter
// tolerance chooses more; a scene whose own settings over-solve gets a
// cheaper choice. Times are never asserted (the cost model's predictions,
// which are deterministic, are).
#include <catch2/catch.hpp>

#include <cmath>
#include <filesystem>
#include <string>
#include <vector>

#include <fmt/format.h>

#include "app/accuracy_control.hpp"
#include "app/accuracy_probe.hpp"
#include "app/convergence.hpp"
#include "app/scene_checks.hpp"
#include "app/simulation.hpp"
#include "io/result_reader.hpp"
#include "model/cloth_builder.hpp"
#include "plan/task_work.hpp"
#include "sched/accuracy_choice.hpp"
#include "solver/method_registry.hpp"
#include "support/temp_dir.hpp"

using namespace atssim;

namespace {

struct SceneCase {
  std::string path;
  std::vector<std::string> overrides;
  int frames = 9;
  int recheck = 3;
  std::vector<std::string> frictionless;  // what converge needs to measure y as the probe does
};

std::string scene(const std::string& name) { return std::string(ATSSIM_SOURCE_DIR) + "/scenes/" + name; }

SceneCase small_hanging_cloth() {
  return {scene("hanging_cloth.yaml"), {"objects.0.grid.resolution=[10, 10]", "devices=cpu"}, 9, 3, {}};
}

// Dropped from 5 cm above the sphere: it touches down in frame 7.
SceneCase small_drape() {
  return {scene("drape_sphere.yaml"),
          {"objects.0.grid.resolution=[12, 12]", "objects.0.transform.translate=[0, 0.8, 0]", "devices=cpu"},
          10,
          3,
          {"colliders.0.friction.static=0", "colliders.0.friction.kinetic=0"}};
}

// A 3x3x3-cell box whose lowest corner starts 7.7 cm above the ground: it
// lands in frame 8.
SceneCase small_box() {
  return {scene("soft_box.yaml"),
          {"objects.0.box.resolution=[3, 3, 3]", "simulation.substeps=4", "objects.0.transform.translate=[0, 0.35, 0]",
           "devices=cpu"},
          12,
          4,
          {}};
}

std::vector<std::string> with(std::vector<std::string> a, const std::vector<std::string>& b) {
  a.insert(a.end(), b.begin(), b.end());
  return a;
}

app::RunResult tuned_run(const SceneCase& c, double tolerance, int frames, const std::string& out) {
  app::RunOptions o;
  o.scene_path = c.path;
  o.overrides =
      with(c.overrides, {"solver.tolerance=" + std::to_string(tolerance), "solver.recheck=" + std::to_string(c.recheck),
                         "simulation.frames=" + std::to_string(frames), "output.path=" + out});
  o.warn = [](const std::string&) {};
  return app::run_simulation(o);
}

// y of a decision's method and iterations, measured by `converge` on the
// state the run in `from` ended at.
double converge_y(const SceneCase& c, const std::string& from, const io::DecisionRecord& d) {
  app::ConvergeOptions o;
  o.scene_path = c.path;
  o.overrides = with(c.overrides, c.frictionless);
  o.methods = {d.method};
  o.schedules = {"single"};
  o.max_iterations = d.iterations;
  o.timing_repeats = 1;
  o.from = from;
  const io::ConvergenceResult r = app::run_convergence(o);
  REQUIRE(r.traces.size() == 1);
  REQUIRE(r.traces[0].iterations.back() == d.iterations);
  return r.traces[0].relative_error.back();
}

bool same_choices(const std::vector<io::DecisionRecord>& a, const std::vector<io::DecisionRecord>& b) {
  if (a.size() != b.size()) return false;
  for (std::size_t i = 0; i < a.size(); ++i) {
    if (a[i].frame != b[i].frame || a[i].method != b[i].method || a[i].iterations != b[i].iterations ||
        a[i].schedule != b[i].schedule || !(a[i].y == b[i].y || (std::isnan(a[i].y) && std::isnan(b[i].y))))
      return false;
  }
  return true;
}

// The done-when of issue 23 on one scene: with --tolerance 1e-2, every
// state that resolves the tolerance gets a choice whose y meets it; the
// last re-check is measured again by converge from the state a run of
// that length ends at (whose decisions, up to there, are the same).
void check_tolerance_holds(const SceneCase& c) {
  constexpr double tolerance = 1e-2;
  test::TempDir dir;
  const app::RunResult full = tuned_run(c, tolerance, c.frames, dir.file("full.h5"));
  const std::vector<io::DecisionRecord>& rows = full.decisions;
  REQUIRE_FALSE(rows.empty());
  CHECK(io::read_decisions(dir.file("full.h5")).size() == rows.size());
  const io::DecisionRecord* last = nullptr;
  for (const io::DecisionRecord& d : rows) {
    INFO("frame " << d.frame << ": " << d.method << " at " << d.iterations << ", y " << d.y << ", floor " << d.y_floor
                  << ": " << d.reason);
    if (!sched::resolves(d.y_floor, tolerance)) continue;  // float32 cannot tell choices apart there
    CHECK(d.y <= tolerance);
    if (d.frame > 0) last = &d;
  }
  REQUIRE(last != nullptr);  // some re-check saw a state that resolves the tolerance
  const std::string prefix = dir.file("prefix.h5");
  const app::RunResult shorter = tuned_run(c, tolerance, last->frame, prefix);
  std::vector<io::DecisionRecord> before;
  for (const io::DecisionRecord& d : rows) {
    if (d.frame < last->frame) before.push_back(d);
  }
  CHECK(same_choices(shorter.decisions, before));  // reproducible
  const double y = converge_y(c, prefix, *last);
  INFO("re-check of frame " << last->frame << ": " << last->method << " at " << last->iterations << " iterations, y "
                            << last->y << " in the run, " << y << " by converge");
  CHECK(y <= tolerance);
  CHECK(y == Approx(last->y).epsilon(1e-3).margin(1e-9));
}

// The probe of `tolerance` on the state the run in `from` ended at.
app::ProbeTable probe_at(const SceneCase& c, const std::string& from, int frame, double tolerance) {
  const scene::SceneDesc s =
      app::load_scene(c.path, with(c.overrides, {"solver.tolerance=" + std::to_string(tolerance)}));
  const device::DeviceSet devices = app::open_scene_devices(s);
  solver::SimLayout state = solver::make_sim_layout(model::build_model(s));
  const io::Checkpoint point = io::read_checkpoint(from);
  state.x = plan::values_of<solver::Float4>(point.positions);
  state.v = plan::values_of<solver::Float4>(point.velocities);
  app::AccuracyProbe probe(s, devices, 1e-3);  // the reference device's speed: times comparable across probes
  return probe.probe(state, frame, 1);
}

// Tighter asks more, and a scene whose own settings over-solve costs less.
void check_tighter_and_cheaper(const SceneCase& c, int frame) {
  test::TempDir dir;
  app::RunOptions o;
  o.scene_path = c.path;
  o.overrides = with(c.overrides, {"simulation.frames=" + std::to_string(frame), "output.path=" + dir.file("run.h5")});
  app::run_simulation(o);
  const app::ProbeTable loose = probe_at(c, dir.file("run.h5"), frame, 1e-2);
  const app::ProbeTable tight = probe_at(c, dir.file("run.h5"), frame, 1e-4);
  REQUIRE(loose.resolved);
  REQUIRE(tight.resolved);
  REQUIRE(loose.choice.chosen);
  const app::SolverChoice a = loose.at(*loose.choice.chosen);
  INFO("1e-2: " << a.method << " at " << a.iterations << ", y " << a.y);
  if (tight.choice.chosen) {
    const app::SolverChoice b = tight.at(*tight.choice.chosen);
    INFO("1e-4: " << b.method << " at " << b.iterations << ", y " << b.y);
    CHECK((b.method != a.method || b.iterations > a.iterations));
    CHECK(b.predicted_ms >= a.predicted_ms);
  }
  REQUIRE(loose.scene_default);
  const app::SolverChoice own = loose.at(*loose.scene_default);
  INFO("the scene's own: " << own.method << " at " << own.iterations << ", y " << own.y);
  if (own.y <= 1e-2) CHECK(a.predicted_ms <= own.predicted_ms);
}

// The modelled cost (µs on the reference device) of one VBD substep of
// `iterations` on one device: the sum of its tasks' costs.
double vbd_substep_us(const SceneCase& c, int iterations) {
  const scene::SceneDesc s = app::load_scene(c.path, with(c.overrides, {"solver.method=vbd"}));
  const solver::MethodDescription& vbd = solver::method("vbd");
  solver::MethodSettings settings = solver::method_settings(s, vbd);
  settings.iterations = iterations;
  const plan::SubstepPlan p = vbd.build(solver::make_sim_layout(model::build_model(s)), settings);
  double us = 0.0;
  for (sched::TaskId t = 0; t < p.graph.size(); ++t) us += plan::task_work_us(p, t);
  return us;
}

}  // namespace

TEST_CASE("run --tolerance 1e-2 holds at every re-check of the hanging cloth, measured by converge", "[accuracy]") {
  check_tolerance_holds(small_hanging_cloth());
}

TEST_CASE("run --tolerance 1e-2 holds at every re-check of the drape, measured by converge", "[accuracy]") {
  check_tolerance_holds(small_drape());
}

TEST_CASE("run --tolerance 1e-2 holds at every re-check of the soft box, measured by converge", "[accuracy]") {
  check_tolerance_holds(small_box());
}

TEST_CASE("a tolerance of 1e-4 chooses more than 1e-2 on each scene, and over-solving defaults get cheaper choices",
          "[accuracy]") {
  check_tighter_and_cheaper(small_hanging_cloth(), 3);
  check_tighter_and_cheaper(small_drape(), 8);
  check_tighter_and_cheaper(small_box(), 10);
}

TEST_CASE("the same scene, devices and flags give the same choices, schedules included", "[accuracy]") {
  SceneCase c = small_hanging_cloth();
  c.overrides = {"objects.0.grid.resolution=[10, 10]", "devices=cpu/2"};
  test::TempDir dir;
  const app::RunResult a = tuned_run(c, 1e-2, 4, dir.file("a.h5"));
  const app::RunResult b = tuned_run(c, 1e-2, 4, dir.file("b.h5"));
  REQUIRE(a.decisions.size() >= 2);
  CHECK(same_choices(a.decisions, b.decisions));
}

TEST_CASE("a resumed run goes on with the choices an uninterrupted run makes", "[accuracy]") {
  const SceneCase c = small_hanging_cloth();
  test::TempDir dir;
  const app::RunResult whole = tuned_run(c, 1e-2, 7, dir.file("whole.h5"));
  app::RunOptions o;
  o.scene_path = c.path;
  o.overrides = with(c.overrides, {"solver.tolerance=" + std::to_string(1e-2), "solver.recheck=3",
                                   "simulation.frames=7", "output.path=" + dir.file("part.h5")});
  o.warn = [](const std::string&) {};
  // Stopped (as by Ctrl-C) after frame 4, past the re-check of frame 3.
  app::RunResult stopped;
  CHECK_THROWS_WITH(app::run_simulation(o, stopped,
                                        [](const app::RunProgress& p) {
                                          if (p.frame == 4) app::request_stop();
                                        }),
                    Catch::Contains("interrupted"));
  o.resume = true;
  const app::RunResult resumed = app::run_simulation(o);
  CHECK(same_choices(resumed.decisions, whole.decisions));
  CHECK(io::read_frame_positions(dir.file("part.h5"), 7) == io::read_frame_positions(dir.file("whole.h5"), 7));
}

TEST_CASE(
    "a budget takes the iterations the cost model fits into it, the same every time, and nothing that fits is "
    "refused before writing",
    "[accuracy]") {
  // The cost model at the reference device's speed (no profile): the choice
  // is then a function of the plan alone. The 10x10 cloth starts at rest,
  // where y cannot rank choices: VBD (the one method listed) takes as many
  // iterations as the budget holds.
  const SceneCase c = small_hanging_cloth();
  test::TempDir dir;
  app::RunOptions o;
  o.scene_path = c.path;
  o.cost_scale = 1e-3;
  o.overrides = with(c.overrides, {"solver.budget_ms=20", "solver.methods=[vbd]", "simulation.frames=1",
                                   "output.path=" + dir.file("a.h5")});
  const app::RunResult a = app::run_simulation(o);
  o.overrides.back() = "output.path=" + dir.file("b.h5");
  const app::RunResult b = app::run_simulation(o);
  REQUIRE(a.decisions.size() == 1);
  CHECK(same_choices(a.decisions, b.decisions));
  // One device, one schedule: a substep costs the sum of its tasks' modelled
  // costs, linear in the iterations; a frame is 16 substeps.
  const double per_iteration = vbd_substep_us(c, 2) - vbd_substep_us(c, 1);
  const double fixed = vbd_substep_us(c, 1) - per_iteration;
  const int fits = static_cast<int>(std::floor((20.0 / 16 / 1e-3 - fixed) / per_iteration));
  CHECK(a.decisions.front().method == "vbd");
  CHECK(a.decisions.front().iterations == fits);
  CHECK(a.decisions.front().predicted_ms == Approx(16e-3 * (fixed + fits * per_iteration)));
  CHECK(a.decisions.front().predicted_ms <= 20.0);

  o.overrides = with(c.overrides, {"solver.budget_ms=1e-3", "output.path=" + dir.file("none.h5")});
  CHECK_THROWS_WITH(app::run_simulation(o), Catch::Contains("no choice fits"));
  CHECK_FALSE(std::filesystem::exists(dir.file("none.h5")));
}

TEST_CASE("a budget below what one iteration's frame costs ends at one iteration and says why", "[accuracy]") {
  // The cost model told the devices are a million times faster than the
  // reference (cost_scale 1e-6 ms per modelled µs): the probe fits 4 VBD
  // iterations into the budget, and the frames measured after frame 3 (16
  // substeps of real kernel launches, far above the budget's ~2 µs) scale
  // them down to the least, one. The run then says why it cannot hold it.
  const SceneCase c = small_hanging_cloth();
  const double per_iteration = vbd_substep_us(c, 2) - vbd_substep_us(c, 1);
  const double fixed = vbd_substep_us(c, 1) - per_iteration;
  const double budget_ms = 16e-6 * (fixed + 4.5 * per_iteration);
  test::TempDir dir;
  app::RunOptions o;
  o.scene_path = c.path;
  o.cost_scale = 1e-6;
  o.overrides = with(c.overrides, {fmt::format("solver.budget_ms={:.17g}", budget_ms), "solver.methods=[vbd]",
                                   "simulation.frames=5", "output.path=" + dir.file("a.h5")});
  std::vector<std::string> warnings;
  o.warn = [&](const std::string& w) { warnings.push_back(w); };
  const app::RunResult a = app::run_simulation(o);
  REQUIRE(a.decisions.size() >= 2);
  CHECK(a.decisions.front().iterations == 4);
  CHECK(a.decisions.back().frame == app::AccuracyControl::kBudgetCalibrationFrame);
  CHECK(a.decisions.back().iterations == 1);
  REQUIRE_FALSE(warnings.empty());
  CHECK_THAT(warnings.back(), Catch::Contains("the median frame took") &&
                                  Catch::Contains("at one iteration of vbd, the least") &&
                                  Catch::Contains("raise --budget or lower simulation.substeps"));
}
