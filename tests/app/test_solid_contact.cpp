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
#include "support/scene_runs.hpp"
#include "support/surface_checks.hpp"
#include "support/temp_dir.hpp"

using namespace atssim;

namespace {

constexpr double kThickness = 0.01;
constexpr int kFrames = 15;
constexpr int kBoxVertices = 27;  // a 2 x 2 x 2 box grid; the lower box's come first

// The lower box (0.2 m) lies on the ground, its top at y = 0.2; the upper
// one, turned by 20 degrees about y, starts 3 cm above it and lands within
// ~5 frames.
const std::string kStack =
    "simulation: {fps: 60, substeps: 8, iterations: 8, frames: " + std::to_string(kFrames) +
    ", ground: 0.0}\n"
    "objects:\n"
    "  - {name: lower, type: solid, box: {size: [0.2, 0.2, 0.2], resolution: [2, 2, 2]},\n"
    "     transform: {translate: [0, 0.1, 0]},\n"
    "     material: {density: 1000, youngs_modulus: 5.0e4, poisson_ratio: 0.3, model: stvk}}\n"
    "  - {name: upper, type: solid, box: {size: [0.2, 0.2, 0.2], resolution: [2, 2, 2]},\n"
    "     transform: {translate: [0.04, 0.33, 0.03], rotate: [0, 20, 0]},\n"
    "     material: {density: 1000, youngs_modulus: 5.0e4, poisson_ratio: 0.3, model: stvk}}\n"
    "contact: {self: true, thickness: 0.01}\n";

std::vector<std::string> contact_methods() {
  std::vector<std::string> names;
  for (const solver::MethodDescription* m : solver::methods()) {
    if (m->colliders) names.emplace_back(m->name);  // the methods with contact tasks
  }
  return names;
}

double lowest_upper(const std::vector<Eigen::Vector3d>& x) {
  double y = 1e9;
  for (std::size_t v = kBoxVertices; v < x.size(); ++v) y = std::min(y, x[v].y());
  return y;
}

double highest_lower(const std::vector<Eigen::Vector3d>& x) {
  double y = -1e9;
  for (std::size_t v = 0; v < kBoxVertices; ++v) y = std::max(y, x[v].y());
  return y;
}

}  // namespace

TEST_CASE("a soft box dropped on another rests on it, the surfaces apart in every frame (every method with contact)",
          "[contact][solid]") {
  const std::string method = GENERATE(from_range(contact_methods()));
  INFO(method);
  const test::Surface surface =
      test::surface_of(model::build_model(scene::parse_scene(kStack, "stack.yaml", ".")));
  test::TempDir dir;
  app::run_simulation(test::options(dir, kStack, method, "single"));
  const std::string out = dir.file("out.h5");
  REQUIRE(test::frame(out, 0).size() == 2 * kBoxVertices);
  double closest = 1e9;
  for (int f = 0; f <= kFrames; ++f) {
    INFO("frame " << f);
    const auto x = test::frame(out, f);
    const test::SurfaceReport r = test::check_surface(surface, x, 2 * kThickness);
    CHECK(r.crossings == 0);
    closest = std::min(closest, r.closest);
    CHECK(lowest_upper(x) > highest_lower(x) - 0.25 * kThickness);  // never into the lower box
  }
  INFO("closest vertex-triangle pair " << closest << " m");
  CHECK(closest >= 0.5 * kThickness);  // kept the contact thickness, give or take half
  // and it did land: at the end it lies within the thickness of the lower box
  const auto last = test::frame(out, kFrames);
  INFO("gap at the end " << lowest_upper(last) - highest_lower(last) << " m");
  CHECK(lowest_upper(last) - highest_lower(last) < 2 * kThickness);
}

TEST_CASE("without contact the dropped box sinks into the lower one (the control of the test above)",
          "[contact][solid]") {
  test::TempDir dir;
  app::RunOptions o = test::options(dir, kStack, "vbd", "single");
  o.overrides.push_back("contact.self=false");
  app::run_simulation(o);
  const auto last = test::frame(dir.file("out.h5"), kFrames);
  INFO("upper box's lowest y " << lowest_upper(last) << ", lower box's top " << highest_lower(last));
  CHECK(lowest_upper(last) < highest_lower(last) - 0.05);
}
