// Explicit integration of mass-spring models (issue #13, seed 001 Eqs. 2-4):
// period, convergence order, the stability limit and the gathered forces.
#include <catch2/catch.hpp>

#include <cmath>
#include <filesystem>
#include <string>
#include <vector>

#include "app/execution.hpp"
#include "app/simulation.hpp"
#include "solver/layout/sim_layout.hpp"
#define ats_float4 ::atssim::solver::Float4
#include "common/vertex_force.h"  // ats_spring_force: the one spring's force
#include "device/device_set.hpp"
#include "io/result_reader.hpp"
#include "model/cloth_builder.hpp"
#include "scene/scene_loader.hpp"
#include "solver/explicit/stability_limit.hpp"
#include "support/temp_dir.hpp"
#include "util/error.hpp"

#include <fmt/format.h>

using namespace atssim;

namespace {

constexpr double kPi = 3.14159265358979323846;

// One mass on one spring (as in test_damping.cpp): a 2 x 2 grid with three
// corners pinned, moved so that the free corner (vertex 3, m = 1/30 kg)
// starts at the origin (small coordinates: float rounding stays far below
// the errors measured). Gravity along +z stretches its spring to vertex 1
// (along z, stiffness k); the spring to vertex 2 is perpendicular.
std::string oscillator_yaml(double k, int substeps, int frames, const std::string& integrator) {
  return "simulation: {fps: 60, substeps: " + std::to_string(substeps) +
         ", iterations: 1, frames: " + std::to_string(frames) +
         ", gravity: [0, 0, 9.81]}\n"
         "objects:\n"
         "  - grid: {size: [1, 1], resolution: [2, 2]}\n"
         "    transform: {translate: [-0.5, 0, -0.5]}\n"
         "    material: {density: 0.2, stretch_stiffness: " +
         std::to_string(k) +
         "}\n"
         "    pins: {vertices: [0, 1, 2]}\n"
         "solver: {method: explicit, integrator: " +
         integrator + ", allow_unstable: true}\n";
}

// z of vertex 3 per frame.
std::vector<double> oscillator_z(const test::TempDir& dir, double k, int substeps, int frames,
                                 const std::string& integrator) {
  app::RunOptions o;
  o.scene_path = dir.write("osc.yaml", oscillator_yaml(k, substeps, frames, integrator));
  o.overrides = {"output.path=" + dir.file("osc.h5"), "devices=cpu"};
  app::run_simulation(o);
  std::vector<double> z;
  for (int f = 0; f <= frames; ++f) z.push_back(io::read_frame_positions(dir.file("osc.h5"), f)[3 * 3 + 2]);
  return z;
}

double largest_difference(const std::vector<double>& a, const std::vector<double>& b) {
  double worst = 0.0;
  for (std::size_t i = 0; i < a.size(); ++i) worst = std::max(worst, std::abs(a[i] - b[i]));
  return worst;
}

}  // namespace

TEST_CASE("explicit RK4: a spring-mass oscillator's period is 2 pi sqrt(m/k) within 1 %", "[explicit][fast]") {
  const double k = 10.0, m = 0.2 * 0.5 / 3.0;
  test::TempDir dir;
  // fps 60 x 40 substeps: h = 1/2400 s, omega h = 0.007.
  const std::vector<double> z = oscillator_z(dir, k, 40, 60, "rk4");
  const double z_eq = m * 9.81 / k;  // about the start z = 0
  // Upward crossings of z_eq, interpolated between frames.
  std::vector<double> crossings;
  for (std::size_t f = 1; f < z.size(); ++f) {
    const double a = z[f - 1] - z_eq, b = z[f] - z_eq;
    if (a < 0.0 && b >= 0.0) crossings.push_back((f - 1 + a / (a - b)) / 60.0);
  }
  REQUIRE(crossings.size() >= 2);
  const double period = (crossings.back() - crossings.front()) / static_cast<double>(crossings.size() - 1);
  const double analytic = 2.0 * kPi * std::sqrt(m / k);
  INFO("period " << period << " s over " << crossings.size() - 1 << " periods, analytic " << analytic << " s");
  CHECK(period == Approx(analytic).epsilon(0.01));
}

TEST_CASE("halving the step shrinks the trajectory error 2x (semi-implicit Euler), 4x (midpoint), 16x (RK4)",
          "[explicit]") {
  struct Case {
    std::string integrator;
    int coarse;  // substeps per frame of the coarsest run
    double order;
  };
  const Case c = GENERATE(Case{"semi_euler", 8, 1.0}, Case{"midpoint", 4, 2.0}, Case{"rk4", 1, 4.0});
  const double k = 100.0;  // omega = 54.8 1/s
  const int frames = 30;
  test::TempDir dir;
  const std::vector<double> reference = oscillator_z(dir, k, 256, frames, "rk4");
  std::vector<double> error;
  for (int s = c.coarse; s <= 4 * c.coarse; s *= 2) {
    error.push_back(largest_difference(oscillator_z(dir, k, s, frames, c.integrator), reference));
  }
  const double first = std::log2(error[0] / error[1]), second = std::log2(error[1] / error[2]);
  INFO(c.integrator << ": errors " << error[0] << ", " << error[1] << ", " << error[2] << " m; orders " << first << ", "
                    << second);
  CHECK(std::abs(first - c.order) < 0.3);
  CHECK(std::abs(second - c.order) < 0.3);
}

namespace {

std::string cloth_yaml(double dt, int frames, const std::string& integrator) {
  return "simulation: {dt: " + fmt::format("{:.17g}", dt) +
         ", substeps: 1, iterations: 1, frames: " + std::to_string(frames) +
         "}\n"
         "objects:\n"
         "  - grid: {size: [1, 1], resolution: [8, 8]}\n"
         "    material: {density: 0.2, stretch_stiffness: 1000, bend_stiffness: 0.001}\n"
         "    pins: {boxes: [{min: [-0.51, -0.01, -0.51], max: [-0.49, 0.01, -0.49]},\n"
         "                   {min: [0.49, -0.01, -0.51], max: [0.51, 0.01, -0.49]}]}\n"
         "solver: {method: explicit, integrator: " +
         integrator + "}\n";
}

double estimated_limit(const std::string& integrator) {
  const auto scene = scene::parse_scene(cloth_yaml(1e-3, 1, integrator), "s.yaml", ".");
  const auto layout = solver::make_sim_layout(model::build_model(scene));
  const auto kind = integrator == "rk4"        ? solver::explicit_rk::Integrator::rk4
                    : integrator == "midpoint" ? solver::explicit_rk::Integrator::midpoint
                                               : solver::explicit_rk::Integrator::semi_euler;
  return solver::explicit_rk::stable_step(kind, solver::explicit_rk::largest_eigenvalue_bound(layout));
}

}  // namespace

TEST_CASE("a cloth at 0.9x the estimated stable step stays finite for 1000 steps and at 3x is refused",
          "[explicit][stability]") {
  const std::string integrator = GENERATE(as<std::string>{}, "semi_euler", "midpoint", "rk4");
  const double limit = estimated_limit(integrator);
  test::TempDir dir;
  app::RunOptions o;
  o.overrides = {"output.path=" + dir.file("ok.h5"), "devices=cpu", "output.stride=1000"};
  o.scene_path = dir.write("ok.yaml", cloth_yaml(0.9 * limit, 1000, integrator));
  app::run_simulation(o);
  const auto x = io::read_frame_positions(dir.file("ok.h5"), 1);
  double largest = 0.0;
  for (float c : x) largest = std::max(largest, double(std::abs(c)));
  INFO(integrator << ": limit " << limit << " s; after 1000 steps at 0.9x the largest coordinate is " << largest);
  CHECK(std::isfinite(largest));
  CHECK(largest < 2.0);

  o.overrides = {"output.path=" + dir.file("bad.h5"), "devices=cpu"};
  o.scene_path = dir.write("bad.yaml", cloth_yaml(3.0 * limit, 1000, integrator));
  try {
    app::run_simulation(o);
    FAIL("3x the stable step ran");
  } catch (const Error& e) {
    const std::string what = e.what();
    INFO(what);
    CHECK(what.find("exceeds the estimated stable step") != std::string::npos);
    CHECK(what.find("simulation.substeps ≥ 3") != std::string::npos);
    CHECK(what.find('\n') == std::string::npos);
  }
  CHECK_FALSE(std::filesystem::exists(dir.file("bad.h5")));
}

namespace {

const char* kHangingSprings =
    "simulation: {fps: 60, substeps: 64, iterations: 1}\n"
    "objects:\n"
    "  - grid: {size: [1, 1], resolution: [9, 7]}\n"
    "    material: {density: 0.2, stretch_stiffness: 1000}\n"
    "    pins: {boxes: [{min: [-0.51, -0.01, -0.51], max: [-0.49, 0.01, -0.49]}]}\n"
    "solver: {method: explicit, integrator: semi_euler}\n";

// After 40 substeps, the positions and the accelerations the next substep
// gathers from them (float4 per particle).
struct Gathered {
  std::vector<float> x;
  std::vector<float> a;
};

Gathered gather(const std::string& devices_spec, app::ScheduleMode mode, const plan::SubstepPlan& plan) {
  const auto devices = device::DeviceSet::open(devices_spec);
  app::ExecutionOptions options;
  options.mode = mode;
  options.executor = device::ExecutorKind::events;
  options.profile_repetitions = 1;
  app::Execution e = app::prepare_execution(devices, plan, options);
  e.executor->run_substeps(40);
  Gathered g;
  g.x = plan::values_of<float>(e.executor->read_state().positions);
  e.executor->run_substeps(1);
  e.executor->finish();
  for (std::size_t b = 0; b < e.plan().buffers.size(); ++b) {
    if (e.plan().buffers[b].name == "acceleration") {
      g.a = plan::values_of<float>(e.executor->read(static_cast<plan::BufferId>(b)));
    }
  }
  return g;
}

}  // namespace

TEST_CASE("the gathered spring force equals a serial sum over the springs exactly, on one and on two devices",
          "[explicit]") {
  const auto scene = scene::parse_scene(kHangingSprings, "s.yaml", ".");
  const plan::SubstepPlan plan = app::substep_plan_for(scene);
  const solver::SimLayout layout = solver::make_sim_layout(model::build_model(scene));
  const auto mode = GENERATE(app::ScheduleMode::single, app::ScheduleMode::split, app::ScheduleMode::heft);
  const Gathered g = gather(mode == app::ScheduleMode::single ? "cpu" : "cpu/2", mode, plan);
  REQUIRE(g.a.size() == g.x.size());
  const std::size_t n = g.x.size() / 4;
  // Serial: every spring in index order adds its force to both ends.
  std::vector<ats_vec3> f(n, ats_v3(0.0f, 0.0f, 0.0f));
  for (const ats_distance_c& c : layout.stretch) {
    const ats_vec3 xa = ats_v3(g.x[4 * c.a], g.x[4 * c.a + 1], g.x[4 * c.a + 2]);
    const ats_vec3 xb = ats_v3(g.x[4 * c.b], g.x[4 * c.b + 1], g.x[4 * c.b + 2]);
    const ats_vec3 fa = ats_spring_force(xa, xb, c.rest, 1.0f / c.compliance);
    f[c.a] = ats_add(f[c.a], fa);
    f[c.b] = ats_sub(f[c.b], fa);
  }
  std::size_t differ = 0;
  double moved = 0.0;
  for (std::size_t i = 0; i < n; ++i) {
    const float w = g.x[4 * i + 3];
    const ats_vec3 a =
        w == 0.0f ? ats_v3(0.0f, 0.0f, 0.0f) : ats_add(ats_v3(0.0f, -9.81f, 0.0f), ats_scale(f[i], w));  // no drag
    differ += (a.x != g.a[4 * i] || a.y != g.a[4 * i + 1] || a.z != g.a[4 * i + 2]) ? 1 : 0;
    moved = std::max(moved, double(std::abs(ats_length(f[i]))));
  }
  INFO(app::to_string(mode) << ": " << differ << " of " << n << " particles differ; largest spring force " << moved);
  CHECK(differ == 0);
  CHECK(moved > 1e-4);  // the springs are stretched (the weight of a particle is ~0.03 N): not all sums are 0
}

TEST_CASE("explicit RK4 on two sub-devices (split, heft) gives the one-device positions bit for bit", "[explicit]") {
  const auto scene =
      scene::parse_scene(kHangingSprings, "s.yaml", ".", std::vector<std::string>{"solver.integrator=rk4"});
  const plan::SubstepPlan plan = app::substep_plan_for(scene);
  const Gathered one = gather("cpu", app::ScheduleMode::single, plan);
  for (const auto mode : {app::ScheduleMode::split, app::ScheduleMode::heft}) {
    const Gathered two = gather("cpu/2", mode, plan);
    INFO(app::to_string(mode));
    CHECK(two.x == one.x);
    CHECK(two.a == one.a);
  }
}
