#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>
#include <numbers>
#include <string>
#include <vector>

#include <fmt/format.h>
#include <Eigen/Core>

#include "app/convergence.hpp"
#include "app/simulation.hpp"
#include "io/result_reader.hpp"
#include "support/descent_checks.hpp"
#include "support/methods.hpp"
#include "support/scene_runs.hpp"
#include "support/temp_dir.hpp"

using namespace atssim;

namespace {

using Eigen::Vector3d;

// Three small cloths dropped onto a sphere, a capsule and a box, one each.
const char* kDrape =
    "simulation: {fps: 60, substeps: 8, iterations: 6, frames: 60}\n"
    "objects:\n"
    "  - {name: over_sphere, grid: {size: [0.4, 0.4], resolution: [8, 8]}, transform: {translate: [-0.8, 0.3, 0]},\n"
    "     material: {density: 0.2, stretch_stiffness: 1000, bend_stiffness: 0.0001}}\n"
    "  - {name: over_capsule, grid: {size: [0.4, 0.4], resolution: [8, 8]}, transform: {translate: [0, 0.2, 0]},\n"
    "     material: {density: 0.2, stretch_stiffness: 1000, bend_stiffness: 0.0001}}\n"
    "  - {name: over_box, grid: {size: [0.4, 0.4], resolution: [8, 8]}, transform: {translate: [0.8, 0.25, 0]},\n"
    "     material: {density: 0.2, stretch_stiffness: 1000, bend_stiffness: 0.0001}}\n"
    "colliders:\n"
    "  - {type: sphere, center: [-0.8, 0, 0], radius: 0.15, thickness: 0.01, friction: 0.3}\n"
    "  - {type: capsule, a: [0, 0, -0.15], b: [0, 0, 0.15], radius: 0.08, thickness: 0.01, friction: 0.3}\n"
    "  - {type: box, center: [0.8, 0, 0], size: [0.3, 0.2, 0.3], thickness: 0.01, friction: 0.3}\n";
constexpr double kThickness = 0.01;

// Distances to the three surfaces, written here from their closed forms
// (not the kernels' header).
double sphere_distance(const Vector3d& x) { return (x - Vector3d(-0.8, 0, 0)).norm() - 0.15; }
double capsule_distance(const Vector3d& x) {
  const Vector3d a(0, 0, -0.15), b(0, 0, 0.15);
  const double t = std::clamp((x - a).dot(b - a) / (b - a).squaredNorm(), 0.0, 1.0);
  return (x - (a + t * (b - a))).norm() - 0.08;
}
double box_distance(const Vector3d& x) {
  const Vector3d q = (x - Vector3d(0.8, 0, 0)).cwiseAbs() - Vector3d(0.15, 0.1, 0.15);
  return q.cwiseMax(0.0).norm() + std::min(q.maxCoeff(), 0.0);
}

using test::frame;

// A 0.1 m cloth patch resting on a plane through the origin tilted by
// `degrees` about z, at the contact thickness above it.
std::string tilted_patch(double degrees, double mu_s, double mu_k) {
  const double t = degrees * std::numbers::pi / 180.0;
  const double th = 0.005;
  return fmt::format(
      "simulation: {{fps: 60, substeps: 8, iterations: 4, frames: 120}}\n"
      "objects:\n"
      "  - grid: {{size: [0.1, 0.1], resolution: [4, 4]}}\n"
      "    transform: {{rotate: [0, 0, {}], translate: [{}, {}, 0]}}\n"
      "    material: {{density: 0.2, stretch_stiffness: 1000, bend_stiffness: 0.0001}}\n"
      "colliders:\n"
      "  - {{type: plane, point: [0, 0, 0], normal: [{}, {}, 0], thickness: {},\n"
      "     friction: {{static: {}, kinetic: {}}}}}\n",
      degrees, -th * std::sin(t), th * std::cos(t), -std::sin(t), std::cos(t), th, mu_s, mu_k);
}

// Mean displacement down the slope of the patch in each frame.
std::vector<double> downhill(const std::string& file, double degrees, std::size_t frames) {
  const double t = degrees * std::numbers::pi / 180.0;
  const Vector3d down(-std::cos(t), -std::sin(t), 0.0);
  std::vector<double> s;
  const std::vector<Vector3d> start = frame(file, 0);
  for (std::size_t f = 0; f <= frames; ++f) {
    const std::vector<Vector3d> x = frame(file, f);
    double sum = 0.0;
    for (std::size_t i = 0; i < x.size(); ++i) sum += (x[i] - start[i]).dot(down);
    s.push_back(sum / x.size());
  }
  return s;
}

using test::options;

}  // namespace

TEST_CASE("cloth dropped on a sphere, a capsule and a box stays out of them (every method, single and heft)",
          "[contact]") {
  const std::string method = GENERATE(from_range(test::methods_taking(kDrape)));
  const std::string schedule = GENERATE("single", "heft");
  INFO(method << "/" << schedule);
  test::TempDir dir;
  app::run_simulation(options(dir, kDrape, method, schedule));
  const std::string out = dir.file("out.h5");
  const std::vector<Vector3d> x = frame(out, 60);
  double deepest = -1.0;
  double closest[3] = {1e9, 1e9, 1e9};
  for (const Vector3d& p : x) {
    REQUIRE(p.allFinite());
    const double d[3] = {sphere_distance(p), capsule_distance(p), box_distance(p)};
    for (int k = 0; k < 3; ++k) {
      deepest = std::max(deepest, kThickness - d[k]);
      closest[k] = std::min(closest[k], d[k]);
    }
  }
  CHECK(deepest <= 0.01 * kThickness);
  // Each cloth lies on its collider (it did not slide off or stay up).
  for (double c : closest) CHECK(c < 1.5 * kThickness);
  // The recorded contact series say the same in every frame.
  const std::vector<double> penetration = io::read_series(out, "/contact/max_penetration");
  const std::vector<double> active = io::read_series(out, "/contact/active");
  REQUIRE(penetration.size() == 61);
  CHECK(*std::max_element(penetration.begin() + 1, penetration.end()) <= 0.01 * kThickness);
  CHECK(active.front() == 0);  // the cloths start in the air
  CHECK(active.back() > 0);
}

TEST_CASE("a patch on a plane tilted by 20 degrees stays put when mu_s > tan 20 (every method, single and heft)",
          "[contact][friction]") {
  const std::string method = GENERATE(from_range(test::methods_taking(tilted_patch(20.0, 0.6, 0.5))));
  const std::string schedule = GENERATE("single", "heft");
  INFO(method << "/" << schedule);
  test::TempDir dir;
  app::run_simulation(options(dir, tilted_patch(20.0, 0.6, 0.5), method, schedule));
  const std::string out = dir.file("out.h5");
  const std::vector<Vector3d> start = frame(out, 0);
  double moved = 0.0;
  for (std::size_t f = 0; f <= 120; f += 10) {
    const std::vector<Vector3d> x = frame(out, f);
    for (std::size_t i = 0; i < x.size(); ++i) moved = std::max(moved, (x[i] - start[i]).norm());
  }
  CHECK(moved < 1e-3);  // 1 mm over 2 s
}

TEST_CASE("a patch on a plane tilted by 20 degrees slides with g (sin - mu_k cos) when mu_k < tan 20",
          "[contact][friction]") {
  const std::string method = GENERATE(from_range(test::methods_taking(tilted_patch(20.0, 0.2, 0.2))));
  const std::string schedule = GENERATE("single", "heft");
  INFO(method << "/" << schedule);
  const double degrees = 20.0, mu = 0.2;
  test::TempDir dir;
  app::run_simulation(options(dir, tilted_patch(degrees, mu, mu), method, schedule));
  const std::vector<double> s = downhill(dir.file("out.h5"), degrees, 120);
  // A quadratic's second difference over frames 30, 75, 120 (0.5 s to 2 s).
  const double dt = 45.0 / 60.0;
  const double measured = (s[120] - 2.0 * s[75] + s[30]) / (dt * dt);
  const double t = degrees * std::numbers::pi / 180.0;
  const double analytic = 9.81 * (std::sin(t) - mu * std::cos(t));
  INFO("measured " << measured << " m/s², analytic " << analytic << " m/s²");
  CHECK(measured == Approx(analytic).epsilon(0.05));
}

namespace {

// tilted_patch with the plane's coefficient `plane` (none: negative) and the
// cloth material's `cloth`, mu_s = mu_k each.
std::string tilted_patch_materials(double plane, double cloth) {
  std::string yaml = tilted_patch(20.0, plane, plane);
  if (plane < 0.0) {
    const std::size_t at = yaml.find(",\n     friction:");
    yaml.replace(at, yaml.find('}', at) + 1 - at, "");
  }
  const std::string material = "bend_stiffness: 0.0001}";
  yaml.replace(yaml.find(material), material.size(), fmt::format("bend_stiffness: 0.0001, friction: {}}}", cloth));
  return yaml;
}

}  // namespace

TEST_CASE("friction per material: a plane without friction takes the cloth's, with both their mean (every method)",
          "[contact][friction]") {
  const std::string method = GENERATE(from_range(test::methods_taking(tilted_patch_materials(-1.0, 0.6))));
  INFO(method);
  {
    test::TempDir dir;  // the plane sets none: the cloth's 0.6 holds the patch
    app::run_simulation(options(dir, tilted_patch_materials(-1.0, 0.6), method, "single"));
    const std::string out = dir.file("out.h5");
    const std::vector<Vector3d> start = frame(out, 0), end = frame(out, 120);
    double moved = 0.0;
    for (std::size_t i = 0; i < end.size(); ++i) moved = std::max(moved, (end[i] - start[i]).norm());
    CHECK(moved < 1e-3);
  }
  // Plane 0.1, cloth 0.3: the mean 0.2, 1.51 m/s² (the plane's alone would
  // give 2.43, the cloth's 0.59).
  test::TempDir dir;
  app::run_simulation(options(dir, tilted_patch_materials(0.1, 0.3), method, "single"));
  const std::vector<double> s = downhill(dir.file("out.h5"), 20.0, 120);
  const double dt = 45.0 / 60.0;
  const double measured = (s[120] - 2.0 * s[75] + s[30]) / (dt * dt);
  const double t = 20.0 * std::numbers::pi / 180.0;
  const double analytic = 9.81 * (std::sin(t) - 0.2 * std::cos(t));
  INFO("measured " << measured << " m/s², analytic " << analytic << " m/s²");
  CHECK(measured == Approx(analytic).epsilon(0.05));
}

TEST_CASE("converge on a cloth resting on a sphere: y falls with iterations against the contact-aware Newton E*",
          "[contact][converge]") {
  // A small cloth dropped onto a frictionless sphere, 20 frames on: it lies
  // on the sphere. E* is the minimum of the incremental potential with the
  // contact energy in it. Frictionless, because friction is no term of the
  // potential: its step after the iterations moves the result off E*.
  test::TempDir dir;
  const std::string yaml =
      "simulation: {fps: 60, substeps: 4, iterations: 8}\n"
      "objects:\n"
      "  - {grid: {size: [0.3, 0.3], resolution: [7, 7]}, transform: {translate: [0, 0.17, 0]},\n"
      "     material: {density: 0.2, stretch_stiffness: 1000, bend_stiffness: 0.0001}}\n"
      "colliders:\n"
      "  - {type: sphere, center: [0, 0, 0], radius: 0.15, thickness: 0.01}\n"
      "solver: {method: vbd}\n";
  const io::ConvergenceResult r = app::run_convergence(test::converge_options(dir, yaml, 64));
  test::check_ends_lower(r);
  // Measured at 64 iterations: VBD 2.3e-4, SOSD 6.8e-3 (contact energy only);
  // JPGD 7.7e-2 (from 0.33): its projection after every iteration moves the
  // iterate off the penalty minimum (without it, its Chebyshev steps climbed
  // from 0.41 to 0.57).
  CHECK(r.traces[0].relative_error.back() < 1e-3);
  CHECK(r.traces[1].relative_error.back() < 0.15);
  CHECK(r.traces[2].relative_error.back() < 2e-2);
}
