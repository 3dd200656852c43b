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

// An expected failure, counted by the suite. JPGD's box hops on the lower
// one instead of resting: at frame 15 its centroid is 0.0807 m above the
// lower box's top (at rest 0.07), its lowest vertex 0.014 m above it, and
// it has slid to x 0.045 (it starts at 0.01). Landing (frames 5-7), its
// bottom layer sinks to 2 mm of the 10 mm thickness and the contact throws
// it back up. Measured with scratch builds and scene changes (8 December):
// - Not the displacement bound, as this comment said before: with the
//   bound's gamma 0.4 (the default), 1 and 1000 (no clamp at all) the box
//   ends 0.0807, 0.0822 and 0.0759 m above.
// - The contact is stiff for the light box: k = 100 m/h^2 with m the mean
//   mass of both boxes' surface vertices, about 2.8 times the upper box's
//   (their vertices weigh 0.30 and 0.064 kg on average). At
//   contact.stiffness 10 or 30 JPGD, SOSD and VBD all rest (0.069-0.070 m);
//   with the lower box as light per vertex as the upper one, JPGD rests
//   (0.0691). At stiffness 1000 neither rests, though no surface crosses:
//   under JPGD the lower box is thrown up (its highest vertex 0.39 m by
//   frame 15, from 0.2), under VBD its top tilts (0.22-0.23 m).
// - At 8 iterations the outcome turns on anything that moves the landing:
//   pair lists made every substep 0.0634, a query radius of 6 thicknesses
//   0.0699, of 4.5 thicknesses 0.0733.
// - The sideways drift is the unconverged step's (a step H_ii^-1 f_i gives
//   momentum until it converges), not contact: the upper box alone on the
//   ground also speeds up sideways, from 0.4 to 1.1 mm a frame over frames
//   6-15 under JPGD, 1.4 to 2.9 SOSD, 0.4 to 0.8 VBD, none under XPBD or
//   JPGD at 16 iterations.
// SOSD passes the test above at 8 iterations (0.0776 m) but would not at
// 12 or 16 (0.0857, 0.0929): its pass is as fragile as JPGD's failure.
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
