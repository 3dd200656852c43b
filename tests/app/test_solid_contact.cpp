// Solid–solid contact (`contact: {self: true}` over the boundary faces of
// tetrahedral bodies, README "Contact between objects"): a soft box dropped
// onto another that lies on the ground comes to rest on it, under every
// method with contact, judged by the brute-force checker in double of
// tests/support/surface_checks.hpp. Without contact the same box sinks into
// the lower one (the control).
#include <catch2/catch.hpp>

#include <algorithm>
#include <string>
#include <vector>

#include "app/simulation.hpp"
#include "model/cloth_builder.hpp"
#include "scene/scene_loader.hpp"
#include "solver/method_registry.hpp"
#include "support/methods.hpp"
#include "support/scene_runs.hpp"
#include "support/surface_checks.hpp"
#include "support/temp_dir.hpp"

using namespace atssim;

namespace {

constexpr double kThickness = 0.01;
constexpr int kFrames = 15;
constexpr int kBoxVertices = 27;  // a 2 x 2 x 2 box grid; the lower box's come first

// The lower box (0.2 m) lies on the ground, its top at y = 0.2; the upper
// one (0.12 m), turned by 20 degrees about y, starts 3 cm above it, inside
// the top face's outline, and lands within ~5 frames.
const std::string kStack = "simulation: {fps: 60, substeps: 8, iterations: 8, frames: " + std::to_string(kFrames) +
                           ", ground: 0.0}\n"
                           "objects:\n"
                           "  - {name: lower, type: solid, box: {size: [0.2, 0.2, 0.2], resolution: [2, 2, 2]},\n"
                           "     transform: {translate: [0, 0.1, 0]},\n"
                           "     material: {density: 1000, youngs_modulus: 1.0e6, poisson_ratio: 0.3, model: stvk}}\n"
                           "  - {name: upper, type: solid, box: {size: [0.12, 0.12, 0.12], resolution: [2, 2, 2]},\n"
                           "     transform: {translate: [0.01, 0.29, 0.01], rotate: [0, 20, 0]},\n"
                           "     material: {density: 1000, youngs_modulus: 1.0e6, poisson_ratio: 0.3, model: stvk}}\n"
                           "contact: {self: true, thickness: 0.01}\n";

double centroid_y(const std::vector<Eigen::Vector3d>& x, std::size_t from, std::size_t to) {
  double y = 0.0;
  for (std::size_t v = from; v < to; ++v) y += x[v].y();
  return y / static_cast<double>(to - from);
}

double highest_lower(const std::vector<Eigen::Vector3d>& x) {
  double y = -1e9;
  for (std::size_t v = 0; v < kBoxVertices; ++v) y = std::max(y, x[v].y());
  return y;
}

// The upper box lands on the lower one and rests there: the surfaces apart
// in every frame, its centroid half its height plus the thickness above the
// lower box's top.
void check_stack(const std::string& method) {
  INFO(method);
  const test::Surface surface = test::surface_of(model::build_model(scene::parse_scene(kStack, "stack.yaml", ".")));
  test::TempDir dir;
  app::run_simulation(test::options(dir, kStack, method, "single"));
  const std::string out = dir.file("out.h5");
  REQUIRE(test::frame(out, 0).size() == 2 * kBoxVertices);
  double closest = 1e9;
  int crossings = 0;
  for (int f = 0; f <= kFrames; ++f) {
    const auto x = test::frame(out, f);
    const test::SurfaceReport r = test::check_surface(surface, x, 2 * kThickness);
    crossings += r.crossings;
    closest = std::min(closest, r.closest);
  }
  const auto last = test::frame(out, kFrames);
  const double above = centroid_y(last, kBoxVertices, 2 * kBoxVertices) - highest_lower(last);
  INFO("closest vertex-triangle pair " << closest << " m, upper centroid " << above
                                       << " m above the lower box's top (0.06 + thickness at rest)");
  CHECK(crossings == 0);
  CHECK(closest >= 0.5 * kThickness);  // measured 9.9 mm under each method
  CHECK(above > 0.05);                 // it rests on the lower box (0.06 is its half height); measured 0.065-0.070
  CHECK(above < 0.08);                 // and it did land
}

}  // namespace

TEST_CASE(
    "a soft box dropped on another rests on it, the surfaces apart in every frame (every method with contact but JPGD)",
    "[contact][solid]") {
  check_stack(GENERATE(from_range(test::method_names(
      [](const solver::MethodDescription& m) { return m.colliders && std::string(m.name) != "jpgd"; }))));
}

// An expected failure, counted by the suite. On the frictionless top the
// unconverged descent methods drift the upper box sideways; since the pair
// lists are kept from one frame to the next (where they were made is
// carried with the state), JPGD's box hops on the lower one instead of
// resting: at frame 15 its centroid is 0.0805 m above the lower box's top
// (at rest 0.07), its lowest vertex 0.019 m above it, its vertical span
// 0.131 m (0.12 at rest), centroid x 0.045 (it starts at 0.01). The cause
// is the displacement bound's margin: an unlisted pair is bounded by its
// list's horizon less 2 D, D the relative displacement since the lists were
// made, which now grows over frames up to (3 r - 1.5 r) / 2 = 7.5 mm where
// the lists were made anew at every frame's start (8 substeps); a build
// without the margin gives 0.0633 m, as the lists made every frame did
// (0.0639 m, x 0.042). The drift itself is the unconverged solve: the upper
// box's horizontal drift by frame 15 halved or better with each doubling of
// the iterations (measured when lists were made every frame), SOSD 0.114 /
// 0.057 / 0.017 / 0.006 m at 8 / 16 / 32 / 64, JPGD 0.067 / 0.027 / 0.010 /
// 0.004, VBD 0.016 / 0.005 / 0.002 / 0.001, XPBD 0 (its projection moves
// both sides of a pair by their inverse masses, so no step gives the pair
// momentum; a descent step H_ii^-1 f_i that has not converged does). SOSD,
// this test's expected failure until then (its box slid off the edge, x
// 0.078 m, 0.048 m above), now rests: 0.074 m above, x 0.039.
TEST_CASE("a soft box dropped on another rests on it under JPGD (known failure: it hops on it)",
          "[contact][solid][!shouldfail]") {
  check_stack("jpgd");
}

TEST_CASE("without contact the dropped box sinks into the lower one (the control of the test above)",
          "[contact][solid]") {
  const test::Surface surface = test::surface_of(model::build_model(scene::parse_scene(kStack, "stack.yaml", ".")));
  test::TempDir dir;
  app::RunOptions o = test::options(dir, kStack, "vbd", "single");
  o.overrides.push_back("contact.self=false");
  app::run_simulation(o);
  int crossings = 0;
  for (int f = 0; f <= kFrames; ++f) {
    crossings += test::check_surface(surface, test::frame(dir.file("out.h5"), f), 2 * kThickness).crossings;
  }
  const auto last = test::frame(dir.file("out.h5"), kFrames);
  const double above = centroid_y(last, kBoxVertices, 2 * kBoxVertices) - highest_lower(last);
  INFO("upper centroid " << above << " m above the lower box's top; " << crossings << " crossings over the frames");
  CHECK(above < 0.0);
  CHECK(crossings > 0);  // on its way in
}
