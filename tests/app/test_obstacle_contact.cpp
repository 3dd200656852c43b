// Kinematic colliders and triangle-mesh obstacles, end to end (issue #12):
// every method, single and heft on the two CPU sub-devices.
#include <catch2/catch.hpp>

#include <algorithm>
#include <array>
#include <cmath>
#include <fstream>
#include <string>
#include <utility>
#include <vector>

#include <fmt/format.h>
#include <Eigen/Core>

#include "app/simulation.hpp"
#include "io/result_reader.hpp"
#include "support/methods.hpp"
#include "support/obstacle_meshes.hpp"
#include "support/scene_runs.hpp"
#include "support/temp_dir.hpp"

using namespace atssim;
using Eigen::Vector3d;

namespace {

using test::frame;

using test::options;

// A cloth pinned at its four corners, and a sphere coming up from below at
// 0.3 m/s that lifts its middle (centre from y = -0.12 to 0.08 in 40 frames).
// Contact stiffness 1000 m/h^2: at the default 100 the penalty methods (VBD)
// let the stretched cloth 1.9 % of the thickness into the sphere.
constexpr double kPushThickness = 0.01, kPushRadius = 0.08, kPushSpeed = 0.3, kPushStart = -0.12;
const char* kPush =
    "simulation: {fps: 60, substeps: 8, iterations: 6, frames: 40}\n"
    "objects:\n"
    "  - grid: {size: [0.5, 0.5], resolution: [9, 9]}\n"
    "    material: {density: 0.2, stretch_stiffness: 200, bend_stiffness: 0.0001}\n"
    "    pins:\n"
    "      boxes:\n"
    "        - {min: [-0.26, -0.01, -0.26], max: [-0.24, 0.01, -0.24]}\n"
    "        - {min: [0.24, -0.01, -0.26], max: [0.26, 0.01, -0.24]}\n"
    "        - {min: [-0.26, -0.01, 0.24], max: [-0.24, 0.01, 0.26]}\n"
    "        - {min: [0.24, -0.01, 0.24], max: [0.26, 0.01, 0.26]}\n"
    "colliders:\n"
    "  - {type: sphere, center: [0, -0.12, 0], radius: 0.08, thickness: 0.01, velocity: [0, 0.3, 0],\n"
    "     stiffness: 1000}\n";

// A 0.1 m patch resting on the top of a wide flat box (top at y = 0) that
// moves along +x at 0.5 m/s.
constexpr double kBoxSpeed = 0.5;
std::string carried_patch(double mu) {
  return fmt::format(
      "simulation: {{fps: 60, substeps: 8, iterations: 4, frames: 60}}\n"
      "objects:\n"
      "  - grid: {{size: [0.1, 0.1], resolution: [4, 4]}}\n"
      "    transform: {{translate: [0, 0.005, 0]}}\n"
      "    material: {{density: 0.2, stretch_stiffness: 1000, bend_stiffness: 0.0001}}\n"
      "colliders:\n"
      "  - {{type: box, center: [0, -0.05, 0], size: [4, 0.1, 1], thickness: 0.005, friction: {},\n"
      "     velocity: [{}, 0, 0]}}\n",
      mu, kBoxSpeed);
}

double mean_x(const std::vector<Vector3d>& x) {
  double s = 0.0;
  for (const Vector3d& p : x) s += p.x();
  return s / x.size();
}

}  // namespace

TEST_CASE("a sphere moving into a pinned cloth keeps every vertex outside it (every method, single and heft)",
          "[contact][kinematic]") {
  const std::string method = GENERATE(from_range(test::methods_taking(kPush)));
  const std::string schedule = GENERATE("single", "heft");
  INFO(method << "/" << schedule);
  test::TempDir dir;
  app::run_simulation(options(dir, kPush, method, schedule));
  const std::string out = dir.file("out.h5");
  double deepest = -1.0, highest = -1.0;
  for (std::size_t f = 0; f <= 40; ++f) {
    const Vector3d centre(0.0, kPushStart + kPushSpeed * f / 60.0, 0.0);  // the pose at the frame's time
    for (const Vector3d& p : frame(out, f)) {
      REQUIRE(p.allFinite());
      deepest = std::max(deepest, kPushThickness - ((p - centre).norm() - kPushRadius));
      if (f == 40) highest = std::max(highest, p.y());
    }
  }
  INFO("deepest " << deepest << " m, highest vertex " << highest << " m");
  CHECK(deepest <= 0.01 * kPushThickness);
  // The sphere's top (0.16 m) lifted the cloth: the middle rides on it.
  CHECK(highest > 0.16 + kPushThickness - 0.005);
}

TEST_CASE("a patch on a box moving sideways is carried at its speed with friction, and stays behind without",
          "[contact][kinematic][friction]") {
  const std::string method = GENERATE(from_range(test::methods_taking(carried_patch(2.0))));
  const std::string schedule = GENERATE("single", "heft");
  INFO(method << "/" << schedule);
  {
    // mu = 2: the patch catches up at mu g = 19.6 m/s^2 within 0.03 s, then
    // sticks; from 0.5 s to 1 s it moves with the box.
    test::TempDir dir;
    app::run_simulation(options(dir, carried_patch(2.0), method, schedule));
    const std::string out = dir.file("out.h5");
    const double speed = (mean_x(frame(out, 60)) - mean_x(frame(out, 30))) / 0.5;
    INFO("speed " << speed << " m/s, box " << kBoxSpeed << " m/s");
    CHECK(speed == Approx(kBoxSpeed).epsilon(0.03));
    for (const Vector3d& p : frame(out, 60)) CHECK(p.y() > 0.0);  // still on the box's top
  }
  {
    // Frictionless: no tangential force, the patch does not move along x.
    test::TempDir dir;
    app::run_simulation(options(dir, carried_patch(0.0), method, schedule));
    const std::string out = dir.file("out.h5");
    const double moved = mean_x(frame(out, 60)) - mean_x(frame(out, 0));
    INFO("moved " << moved << " m along x");
    CHECK(std::abs(moved) < 1e-3);
  }
}

TEST_CASE("with a moving collider the events and fused executors give the same positions", "[contact][kinematic]") {
  const std::string schedule = GENERATE("single", "split", "heft");
  INFO(schedule);
  test::TempDir dir;
  std::vector<std::vector<float>> last;
  // events and fused on fine-grain SVM, then events on coarse-grain SVM (map/unmap writes)
  for (const auto& [executor, svm] : {std::pair{"events", ""}, std::pair{"fused", ""}, std::pair{"events", "coarse"}}) {
    app::RunOptions o = options(dir, kPush, "xpbd", schedule);
    o.overrides.push_back(std::string("solver.executor=") + executor);
    o.overrides.push_back("simulation.frames=20");
    o.svm_mode = svm;
    app::run_simulation(o);
    last.push_back(io::read_frame_positions(dir.file("out.h5"), 20));
  }
  CHECK(last[0] == last[1]);
  CHECK(last[0] == last[2]);
  // and the sphere did move: the cloth is not where a still sphere leaves it
  app::RunOptions still = options(dir, kPush, "xpbd", schedule);
  still.overrides.push_back("colliders.0.velocity=[0, 0, 0]");
  still.overrides.push_back("simulation.frames=20");
  app::run_simulation(still);
  CHECK(io::read_frame_positions(dir.file("out.h5"), 20) != last[0]);
}

namespace {

// Two cloths, one dropped on an icosphere mesh (closed), one on a flat
// sheet mesh (open), with friction.
constexpr double kMeshThickness = 0.01;
const Vector3d kSphereAt(-0.6, 0.0, 0.0), kSheetAt(0.6, 0.0, 0.0);
std::string mesh_drape(const test::TempDir& dir) {
  test::write_obj(dir.file("ball.obj"), test::obstacle_icosphere(0.15, 2));
  test::write_obj(dir.file("sheet.obj"), test::sheet(0.6, 4));
  return "simulation: {fps: 60, substeps: 8, iterations: 6, frames: 60}\n"
         "objects:\n"
         "  - {name: over_ball, grid: {size: [0.4, 0.4], resolution: [8, 8]}, transform: {translate: [-0.6, 0.2, 0]},\n"
         "     material: {density: 0.2, stretch_stiffness: 1000, bend_stiffness: 0.0001}}\n"
         "  - {name: over_sheet, grid: {size: [0.3, 0.3], resolution: [6, 6]}, transform: {translate: [0.6, 0.1, 0]},\n"
         "     material: {density: 0.2, stretch_stiffness: 1000, bend_stiffness: 0.0001}}\n"
         "colliders:\n"
         "  - {type: mesh, file: ball.obj, position: [-0.6, 0, 0], thickness: 0.01, friction: 0.3}\n"
         "  - {type: mesh, file: sheet.obj, position: [0.6, 0, 0], thickness: 0.01, friction: 0.5}\n";
}

}  // namespace

TEST_CASE("cloth dropped on a closed and an open mesh obstacle stays out of both (every method, single and heft)",
          "[contact][mesh]") {
  const std::string method = GENERATE(from_range([] {
    test::TempDir d;  // the meshes the scene names
    return test::methods_taking(mesh_drape(d), {}, d.path().string());
  }()));
  const std::string schedule = GENERATE("single", "heft");
  INFO(method << "/" << schedule);
  test::TempDir dir;
  app::run_simulation(options(dir, mesh_drape(dir), method, schedule));
  const std::string out = dir.file("out.h5");
  const test::SimpleMesh ball = test::obstacle_icosphere(0.15, 2), sheet = test::sheet(0.6, 4);
  double deepest = -1.0, closest_ball = 1e9, closest_sheet = 1e9;
  for (std::size_t f : {30u, 45u, 60u}) {
    for (const Vector3d& p : frame(out, f)) {
      REQUIRE(p.allFinite());
      const double to_ball = test::mesh_distance(ball, kSphereAt, p);
      const double to_sheet = test::mesh_distance(sheet, kSheetAt, p);
      // The ball's inside counts as deep: no vertex got there.
      CHECK((p - kSphereAt).norm() > 0.15 * 0.9);
      deepest = std::max({deepest, kMeshThickness - to_ball, kMeshThickness - to_sheet});
      closest_ball = std::min(closest_ball, to_ball);
      closest_sheet = std::min(closest_sheet, to_sheet);
    }
  }
  INFO("deepest " << deepest << " m; closest to the ball " << closest_ball << ", to the sheet " << closest_sheet);
  CHECK(deepest <= 0.01 * kMeshThickness);
  CHECK(closest_ball < 1.5 * kMeshThickness);  // each cloth lies on its obstacle
  CHECK(closest_sheet < 1.5 * kMeshThickness);
  const std::vector<double> penetration = io::read_series(out, "/contact/max_penetration");
  REQUIRE(penetration.size() == 61);
  CHECK(*std::max_element(penetration.begin(), penetration.end()) <= 0.01 * kMeshThickness);
}

namespace {

// scenes/funnel.yaml made small: one cloth over the funnel mesh (open,
// scenes/meshes/funnel.obj) and the kinematic sphere pushing it down into
// the spout along keyframes. Contact stiffness 1000 m/h^2: at the default
// 100 SOSD let the squeezed cloth 1.04 % of the thickness into the sphere.
constexpr double kFunnelThickness = 0.005;
std::string small_funnel() {
  return fmt::format(
      "simulation: {{fps: 60, substeps: 10, iterations: 6, frames: 60}}\n"
      "objects:\n"
      "  - grid: {{size: [0.5, 0.5], resolution: [9, 9]}}\n"
      "    transform: {{translate: [0, 1.05, 0]}}\n"
      "    material: {{density: 0.2, stretch_stiffness: 1000, bend_stiffness: 0.0001}}\n"
      "colliders:\n"
      "  - {{type: mesh, file: {}/scenes/meshes/funnel.obj, position: [0, 0.5, 0], thickness: 0.005,\n"
      "     friction: 0.2, stiffness: 1000}}\n"
      "  - {{type: sphere, center: [0, 1.3, 0], radius: 0.09, thickness: 0.005, stiffness: 1000,\n"
      "     keyframes: [{{time: 0, position: [0, 1.3, 0]}}, {{time: 1, position: [0, 0.6, 0]}}]}}\n",
      ATSSIM_SOURCE_DIR);
}

// The funnel of scripts/make_meshes.py as its OBJ file has it.
test::SimpleMesh read_obj(const std::string& path) {
  test::SimpleMesh m;
  std::ifstream in(path);
  for (std::string tag; in >> tag;) {
    if (tag == "v") {
      std::array<double, 3> v{};
      in >> v[0] >> v[1] >> v[2];
      m.vertices.push_back(v);
    } else if (tag == "f") {
      std::array<int, 3> f{};
      in >> f[0] >> f[1] >> f[2];
      m.triangles.push_back({f[0] - 1, f[1] - 1, f[2] - 1});
    } else {
      std::getline(in, tag);
    }
  }
  return m;
}

}  // namespace

TEST_CASE(
    "a sphere on keyframes pushes cloth into a funnel mesh, no vertex gets into the funnel's or the sphere's "
    "thickness (every method, single and heft)",
    "[contact][mesh][kinematic]") {
  const std::string method = GENERATE(from_range(test::methods_taking(small_funnel())));
  const std::string schedule = GENERATE("single", "heft");
  INFO(method << "/" << schedule);
  test::TempDir dir;
  app::run_simulation(options(dir, small_funnel(), method, schedule));
  const std::string out = dir.file("out.h5");
  const test::SimpleMesh funnel = read_obj(std::string(ATSSIM_SOURCE_DIR) + "/scenes/meshes/funnel.obj");
  REQUIRE(funnel.triangles.size() > 100);
  double deepest = -1.0, lowest = 1e9;
  for (std::size_t f : {20u, 40u, 60u}) {
    const double t = std::min(1.0, f / 60.0);
    const Vector3d centre(0.0, 1.3 - 0.7 * t, 0.0);
    for (const Vector3d& p : frame(out, f)) {
      REQUIRE(p.allFinite());
      const double to_funnel = test::mesh_distance(funnel, Vector3d(0, 0.5, 0), p);
      const double to_sphere = (p - centre).norm() - 0.09;
      deepest = std::max({deepest, kFunnelThickness - to_funnel, kFunnelThickness - to_sphere});
      if (f == 60) lowest = std::min(lowest, p.y());
    }
  }
  INFO("deepest " << deepest << " m; lowest vertex at the end " << lowest << " m");
  CHECK(deepest <= 0.01 * kFunnelThickness);
  CHECK(lowest < 0.6);  // pushed down into the spout (it starts at y = 0.5 and the mouth is at 1.0)
}
