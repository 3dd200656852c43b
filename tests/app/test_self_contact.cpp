// Contact between simulated surfaces (scene `contact: {self: true}`), end
// to end: every method, one device and HEFT on two sub-devices, judged by a
// brute-force checker in double (tests/support/surface_checks.hpp: its own
// point-triangle distance and segment-triangle crossing, not the kernels' header).
#include <catch2/catch.hpp>

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <map>
#include <numbers>
#include <string>
#include <tuple>
#include <vector>

#include <fmt/format.h>
#include <Eigen/Core>
#include <Eigen/Geometry>

#include "app/convergence.hpp"
#include "app/simulation.hpp"
#include "io/result_reader.hpp"
#include "model/cloth_builder.hpp"
#include "scene/scene_loader.hpp"
#include "support/cli_runs.hpp"
#include "support/curved_meshes.hpp"
#include "support/descent_checks.hpp"
#include "support/methods.hpp"
#include "support/scene_runs.hpp"
#include "support/surface_checks.hpp"
#include "support/temp_dir.hpp"

using namespace atssim;

namespace {

using Eigen::Vector3d;

constexpr double kThickness = 0.01;

// Two cloth layers, the upper one turned by 30°, dropped onto a sphere.
const char* kLayers =
    "simulation: {fps: 60, substeps: 8, iterations: 6, frames: 40}\n"
    "objects:\n"
    "  - {name: lower, grid: {size: [0.4, 0.4], resolution: [8, 8]}, transform: {translate: [0, 0.2, 0]},\n"
    "     material: {density: 0.2, stretch_stiffness: 1000, bend_stiffness: 0.0001}}\n"
    "  - {name: upper, grid: {size: [0.4, 0.4], resolution: [8, 8]},\n"
    "     transform: {rotate: [0, 30, 0], translate: [0.02, 0.26, 0.01]},\n"
    "     material: {density: 0.2, stretch_stiffness: 1000, bend_stiffness: 0.0001}}\n"
    "colliders:\n"
    "  - {type: sphere, center: [0, 0, 0], radius: 0.12, thickness: 0.01, friction: 0.5}\n"
    "contact: {self: true, thickness: 0.01}\n";

// A sheet dropped on its edge onto a plane: it buckles and folds onto itself.
const char* kFold =
    "simulation: {fps: 60, substeps: 8, iterations: 6, frames: 60}\n"
    "objects:\n"
    "  - {name: sheet, grid: {size: [0.4, 0.4], resolution: [10, 10]}, transform: {rotate: [84, 0, 0], translate: [0, "
    "0.22, 0]},\n"
    "     material: {density: 0.2, stretch_stiffness: 1000, bend_stiffness: 0.00001}}\n"
    "colliders:\n"
    "  - {type: plane, point: [0, 0, 0], normal: [0, 1, 0], thickness: 0.005}\n"
    "contact: {self: true, thickness: 0.01}\n";

// A single quad tilted over a pinned quad 1 m wide, falling onto it: every
// vertex of the small quad that comes near the floor quad lies over the
// inside of one of its triangles, 4 cm or more from its diagonal and edges
// (farther than the query radius, 3 thicknesses), and the small quad's own
// pairs are all incident or sheet neighbours, so each such vertex has one
// pair in all: a point over one triangle.
const char* kQuadOnQuad =
    "simulation: {fps: 60, substeps: 8, iterations: 6, frames: 30}\n"
    "objects:\n"
    "  - {name: floor, grid: {size: [1, 1], resolution: [2, 2]}, pins: {vertices: [0, 1, 2, 3]},\n"
    "     material: {density: 0.2, stretch_stiffness: 1000, bend_stiffness: 0.0001}}\n"
    "  - {name: quad, grid: {size: [0.1, 0.1], resolution: [2, 2]},\n"
    "     transform: {rotate: [20, 0, 10], translate: [0.3, 0.06, 0.1]},\n"
    "     material: {density: 0.2, stretch_stiffness: 1000, bend_stiffness: 0.0001}}\n"
    "contact: {self: true, thickness: 0.01}\n";

// The same sheet onto a floor with friction (its bottom edge stays where it
// lands, so the sheet buckles instead of tipping over and sliding away).
const std::string kFoldOnFriction = [] {
  std::string yaml = kFold;
  const std::string plane = "thickness: 0.005}";
  return yaml.replace(yaml.find(plane), plane.size(), "thickness: 0.005, friction: 0.8}");
}();

using test::point_triangle;
using test::segment_crosses;
using test::Surface;

Surface surface_of(const std::string& yaml) {
  return test::surface_of(model::build_model(scene::parse_scene(yaml, "scene.yaml", ".")));
}

using test::frame;

struct SurfaceCheck {
  double closest = std::numeric_limits<double>::infinity();  // smallest vertex-triangle distance, non-incident
  int crossings = 0;                                         // edges through triangles they do not touch
  int frame_of_closest = -1;
};

void check_frame(const Surface& s, const std::vector<Vector3d>& x, int f, SurfaceCheck& out) {
  for (const auto& t : s.tris) {
    for (std::size_t v = 0; v < x.size(); ++v) {
      if (int(v) == t[0] || int(v) == t[1] || int(v) == t[2]) continue;
      const double d = point_triangle(x[v], x[t[0]], x[t[1]], x[t[2]]);
      if (d < out.closest) {
        out.closest = d;
        out.frame_of_closest = f;
      }
    }
    for (const auto& e : s.edges) {
      if (e[0] == t[0] || e[0] == t[1] || e[0] == t[2] || e[1] == t[0] || e[1] == t[1] || e[1] == t[2]) continue;
      if (segment_crosses(x[e[0]], x[e[1]], x[t[0]], x[t[1]], x[t[2]])) ++out.crossings;
    }
  }
}

SurfaceCheck check_run(const Surface& s, const std::string& file, int frames) {
  SurfaceCheck out;
  for (int f = 0; f <= frames; ++f) check_frame(s, frame(file, f), f, out);
  return out;
}

using test::options;

// Whether the sheet folded onto itself: some vertex within 2 thicknesses of
// a triangle that started more than 0.1 m away from it.
// The smallest distance of a vertex to a triangle 0.1 m or more away from it at rest.
double closest_far_pair(const Surface& s, const std::vector<Vector3d>& x0, const std::vector<Vector3d>& x) {
  double closest = std::numeric_limits<double>::infinity();
  for (const auto& t : s.tris) {
    for (std::size_t v = 0; v < x.size(); ++v) {
      if (point_triangle(x0[v], x0[t[0]], x0[t[1]], x0[t[2]]) < 0.1) continue;
      closest = std::min(closest, point_triangle(x[v], x[t[0]], x[t[1]], x[t[2]]));
    }
  }
  return closest;
}

bool folded_onto_itself(const Surface& s, const std::vector<Vector3d>& x0, const std::vector<Vector3d>& x) {
  return closest_far_pair(s, x0, x) < 2 * kThickness;
}

}  // namespace

// The sheet falls on its edge onto a floor with friction and buckles; the
// fold is judged by the smallest distance of a vertex to a triangle 0.1 m or
// more away from it at rest (folded: < 2 thicknesses = 0.02 m). On a
// frictionless floor a sheet may as well tip over and slide away flat, which
// VBD and SOSD did (0.126): no fold to test there.
void check_folds(const std::string& method) {
  INFO(method);
  test::TempDir dir;
  app::run_simulation(options(dir, kFoldOnFriction, method, "single"));
  const std::string out = dir.file("out.h5");
  const Surface s = surface_of(kFoldOnFriction);
  INFO("closest far pair " << closest_far_pair(s, frame(out, 0), frame(out, 60)) << " m");
  CHECK(folded_onto_itself(s, frame(out, 0), frame(out, 60)));
}

TEST_CASE("the falling sheet folds onto itself (VBD, JPGD)", "[contact][self][fold]") {
  check_folds(GENERATE("vbd", "jpgd"));
}

// An expected failure, counted by the suite. Which way a sheet dropped on
// its edge buckles is chaotic: over substeps {8, 12, 16, 24, 32} x
// iterations {6, 10, 20} (scripts/fold_rate.py) it ended folded (closest
// far pair < 2 thicknesses at frame 60) in 15 of 15 runs under VBD, 14 of 15
// JPGD, 12 of 15 SOSD and 6 of 15 XPBD; this scene's 8 x 6 is one of the
// runs where XPBD (0.035 m) and SOSD (0.042 m) end as a row of tents a
// grid spacing wide instead. Not "hinges held open", as this comment once
// said: the same XPBD folds its layers to 0.0100-0.0105 m at 8 x 20, 12 x 6 and
// 24 x 6, and every method closes the fold below (the napkin) to the
// thickness. Why XPBD lands in tents more often than VBD is not isolated.
TEST_CASE("the falling sheet folds onto itself (XPBD, SOSD: known failure, chaotic at 8 x 6)",
          "[contact][self][fold][!shouldfail]") {
  check_folds(GENERATE("xpbd", "sosd"));
}

namespace {

// A napkin folded by gravity: a 0.4 x 0.4 m sheet creased along its middle,
// one half flat on a floor with friction, the other rising from the crease
// at 60 degrees and leaning over it (an OBJ of 11 x 11 vertices, mesh
// spacing 0.04 m, so the crease has a dihedral rest angle; bending
// 1e-5 N m is far below gravity's torque on the half, 0.02 N m/m). The
// half falls onto the flat one: the fold must close to the thickness and
// the layers must not cross or come within less than it.
const char* kNapkin =
    "simulation: {fps: 60, substeps: 8, iterations: 6, frames: 60}\n"
    "objects:\n"
    "  - {name: sheet, mesh: napkin.obj, material: {density: 0.2, stretch_stiffness: 1000, bend_stiffness: 0.00001}}\n"
    "colliders:\n"
    "  - {type: plane, point: [0, 0, 0], normal: [0, 1, 0], thickness: 0.005, friction: 0.8}\n"
    "contact: {self: true, thickness: 0.01}\n";

}  // namespace

// Measured at commit time, every method, single and heft: the closest far
// pair and the closest non-incident pair both at 0.009975-0.010000 m, no
// crossing (brute force in double, tests/support/surface_checks.hpp).
TEST_CASE("a creased sheet folds flat onto itself, layers a thickness apart (every method, single and heft)",
          "[contact][self][fold]") {
  test::TempDir dir;
  dir.write("napkin.obj", test::creased_sheet(0.2, 11, std::numbers::pi / 3, 0.0101).obj_text());
  const std::string root = dir.path().string();
  const Surface s = test::surface_of(model::build_model(scene::parse_scene(kNapkin, root + "/scene.yaml", root)));
  REQUIRE(s.tris.size() == 200);
  const std::vector<std::string> methods = test::methods_taking([](const std::string&) { return kNapkin; }, {}, root);
  REQUIRE(methods.size() >= 4);  // xpbd, vbd, sosd and jpgd at least
  for (const std::string& method : methods) {
    for (const std::string schedule : {"single", "heft"}) {
      INFO(method << "/" << schedule);
      const std::string name = fmt::format("{}-{}.h5", method, schedule);
      app::run_simulation(options(dir, kNapkin, method, schedule, name));
      const std::string out = dir.file(name);
      const std::vector<Vector3d> x0 = frame(out, 0), x = frame(out, 60);
      INFO("closest far pair " << closest_far_pair(s, x0, x) << " m");
      CHECK(folded_onto_itself(s, x0, x));
      SurfaceCheck c;
      check_frame(s, x, 60, c);
      INFO("closest non-incident vertex-triangle distance " << c.closest << " m");
      CHECK(c.crossings == 0);
      CHECK(c.closest >= 0.99 * kThickness);
    }
  }
}

TEST_CASE("the surface checker of these tests finds a crossing and a close pair it is shown", "[contact][self]") {
  // Its own test: a checker that can never fail would pass any run.
  const Vector3d a(0, 0, 0), b(1, 0, 0), c(0, 0, 1);
  CHECK(segment_crosses(Vector3d(0.2, -0.1, 0.2), Vector3d(0.2, 0.1, 0.2), a, b, c));
  CHECK_FALSE(segment_crosses(Vector3d(0.8, -0.1, 0.8), Vector3d(0.8, 0.1, 0.8), a, b, c));
  CHECK(point_triangle(Vector3d(0.2, 0.003, 0.2), a, b, c) == Approx(0.003));
  CHECK(point_triangle(Vector3d(2, 0, 0), a, b, c) == Approx(1.0));
  CHECK(point_triangle(Vector3d(1, 1, 1), a, b, c) == Approx(std::sqrt(1.5)));
}

TEST_CASE(
    "two cloth layers dropped onto a sphere keep half the thickness apart, never cross, and with "
    "self-contact on stay out of the sphere (every method, single and heft)",
    "[contact][self]") {
  const std::string method = GENERATE(from_range(test::methods_taking(kLayers)));
  const std::string schedule = GENERATE("single", "heft");
  INFO(method << "/" << schedule);
  test::TempDir dir;
  app::run_simulation(options(dir, kLayers, method, schedule));
  const std::string out = dir.file("out.h5");
  const Surface s = surface_of(kLayers);
  const SurfaceCheck c = check_run(s, out, 40);
  INFO("closest vertex-triangle distance " << c.closest << " m in frame " << c.frame_of_closest);
  CHECK(c.crossings == 0);
  CHECK(c.closest >= 0.5 * kThickness);
  // Self-contact and the obstacle together: no vertex deeper than 1 % of
  // the collider's thickness inside the sphere, in any frame.
  double deepest = -1.0;
  for (int f = 0; f <= 40; ++f) {
    for (const Vector3d& p : frame(out, f)) deepest = std::max(deepest, kThickness - (p.norm() - 0.12));
  }
  INFO("deepest " << deepest << " m inside the sphere's thickened surface");
  CHECK(deepest <= 0.01 * kThickness);
  // The layers met: in some frame two surfaces came within two thicknesses
  // (a flat 8 × 8 layer's own non-incident pairs are a grid spacing apart).
  // Where they end is not checked: the upper layer may slide off the sphere
  // (VBD and XPBD leave them ~15 cm apart after 40 frames, JPGD 2 cm).
  CHECK(c.closest < 2 * kThickness);
}

TEST_CASE("a sheet falling on its edge with self-contact stays intersection-free (every method, single and heft)",
          "[contact][self]") {
  const std::string method = GENERATE(from_range(test::methods_taking(kFold)));
  const std::string schedule = GENERATE("single", "heft");
  INFO(method << "/" << schedule);
  test::TempDir dir;
  app::run_simulation(options(dir, kFold, method, schedule));
  const std::string out = dir.file("out.h5");
  const Surface s = surface_of(kFold);
  const SurfaceCheck c = check_run(s, out, 60);
  INFO("closest vertex-triangle distance " << c.closest << " m in frame " << c.frame_of_closest);
  CHECK(c.crossings == 0);
  CHECK(c.closest >= 0.5 * kThickness);
  double lowest = 1e9;  // the plane's thickness is 0.005
  for (int f = 0; f <= 60; ++f) {
    for (const Vector3d& p : frame(out, f)) lowest = std::min(lowest, p.y());
  }
  CHECK(lowest >= 0.005 * 0.99);
}

// Each vertex of the quad holds one contact pair (kQuadOnQuad): a solve
// that passed over a vertex with a single pair (a packed count read one off,
// say) lets the quad sink into the floor's thickness or through it: so it
// did under VBD, JPGD and SOSD with every single-pair vertex skipped.
TEST_CASE("one pair a vertex holds a quad a thickness above another (every method, single and heft)",
          "[contact][self]") {
  const std::string method = GENERATE(from_range(test::methods_taking(kQuadOnQuad)));
  const std::string schedule = GENERATE("single", "heft");
  INFO(method << "/" << schedule);
  test::TempDir dir;
  app::run_simulation(options(dir, kQuadOnQuad, method, schedule));
  const std::string out = dir.file("out.h5");
  const Surface s = surface_of(kQuadOnQuad);
  CHECK(check_run(s, out, 30).crossings == 0);
  // At the last frame the quad lies on the floor (y = 0): every vertex a
  // thickness above it, within 1 %, and none far above (it has landed).
  const std::vector<Vector3d> x = frame(out, 30);
  for (std::size_t v = 4; v < x.size(); ++v) {
    INFO("vertex " << v << " at " << x[v].transpose());
    CHECK(x[v].y() >= 0.99 * kThickness);
    CHECK(x[v].y() <= 1.5 * kThickness);
  }
}

// VBD's colours ignore contact pairs; before its solve read a partner of
// its own colour from the iteration's start, two runs on the whole 2-CU
// device ended 8 cm apart after 20 frames.
TEST_CASE("with self-contact every method gives the same bits on one device and cut over two", "[contact][self]") {
  const std::string method = GENERATE(from_range(test::methods_taking(kLayers)));
  const std::string schedule = GENERATE("split", "heft");
  INFO(method << "/" << schedule);
  test::TempDir dir;
  std::string yaml = kLayers;
  yaml.replace(yaml.find("frames: 40"), 10, "frames: 10");
  app::run_simulation(options(dir, yaml, method, "single", "one.h5"));
  app::run_simulation(options(dir, yaml, method, schedule, "two.h5"));
  app::RunOptions whole = options(dir, yaml, method, "single", "whole.h5");  // one device of two cores
  whole.overrides.push_back("devices=cpu");
  app::run_simulation(whole);
  const std::vector<float> one = io::read_frame_positions(dir.file("one.h5"), 10);
  CHECK(one == io::read_frame_positions(dir.file("two.h5"), 10));
  CHECK(one == io::read_frame_positions(dir.file("whole.h5"), 10));
}

// VBD's color_batches gather 8 vertices of a colour as float lanes, JPGD's
// vertex_batches 8 consecutive vertices; the contact terms, the solve and
// the clamps follow per vertex as in the one-vertex orderings. SOSD's
// color_batches solve 8 bending stencils of a colour as lanes.
TEST_CASE(
    "with and without self-contact the lanes orderings (VBD color_batches, JPGD vertex_batches, SOSD color_batches) "
    "give the one-element orderings' bits, on one device and cut over two",
    "[contact][self]") {
  // The sphere's collider terms follow the lanes' gather vertex by vertex,
  // with or without the surfaces' pairs.
  const bool self = GENERATE(true, false);
  // Named from the row rather than bound to it: a lambda below captures them.
  const auto row = GENERATE(table<std::string, std::string, std::string>({{"vbd", "colors", "color_batches"},
                                                                          {"jpgd", "vertices", "vertex_batches"},
                                                                          {"sosd", "colors", "color_batches"}}));
  const std::string& method = std::get<0>(row);
  const std::string& scalar = std::get<1>(row);
  const std::string& lanes = std::get<2>(row);
  INFO(method << ", contact.self " << self);
  test::TempDir dir;
  std::string yaml = kLayers;
  yaml.replace(yaml.find("frames: 40"), 10, "frames: 10");
  if (!self) yaml.replace(yaml.find("self: true"), 10, "self: false");
  const auto run = [&](const std::string& ordering, const std::string& schedule) {
    const std::string out = ordering + "_" + schedule + ".h5";
    app::RunOptions o = options(dir, yaml, method, schedule, out);
    o.overrides.push_back("solver.ordering=" + ordering);
    app::run_simulation(o);
    return io::read_frame_positions(dir.file(out), 10);
  };
  const std::vector<float> one = run(scalar, "single");
  CHECK(one == run(lanes, "single"));
  CHECK(one == run(lanes, "split"));
  CHECK(one == run(lanes, "heft"));
}

namespace {

constexpr int kPillowCloth = 16;  // cloth vertices per side at the tests' size

std::vector<std::string> small_pillows(const test::TempDir& dir, const std::string& method, const std::string& schedule,
                                       const std::string& output, bool contact) {
  std::vector<std::string> o = {"output.path=" + dir.file(output),
                                "devices=cpu/2",
                                "solver.method=" + method,
                                "solver.schedule=" + schedule,
                                "simulation.frames=50",
                                "simulation.substeps=8",
                                fmt::format("objects.0.grid.resolution=[{0}, {0}]", kPillowCloth),
                                "objects.1.box.resolution=[3, 1, 2]",
                                "objects.2.box.resolution=[3, 1, 2]",
                                std::string("contact.self=") + (contact ? "true" : "false")};
  // The pillows are neo-Hookean where the method simulates it, else StVK (XPBD).
  if (!solver::method(method).simulates(scene::SolidModel::neo_hookean)) {
    o.push_back("objects.1.material.model=stvk");
    o.push_back("objects.2.material.model=stvk");
  }
  return o;
}

// The methods that run the pillows: contact, and neo-Hookean or StVK solids.
bool takes_pillows(const solver::MethodDescription& m) {
  return m.colliders && (m.simulates(scene::SolidModel::neo_hookean) || m.simulates(scene::SolidModel::stvk));
}

// Height of the cloth surface below (x, z): the first cloth triangle whose
// projection onto the xz plane holds the point, interpolated; NaN if none.
double cloth_height_below(const Surface& cloth, const std::vector<Vector3d>& x, double px, double pz) {
  for (const auto& t : cloth.tris) {
    const Eigen::Vector2d a(x[t[0]].x(), x[t[0]].z()), b(x[t[1]].x(), x[t[1]].z()), c(x[t[2]].x(), x[t[2]].z());
    const Eigen::Vector2d p(px, pz);
    const auto cross = [](const Eigen::Vector2d& u, const Eigen::Vector2d& v) { return u.x() * v.y() - u.y() * v.x(); };
    const double area = cross(b - a, c - a);
    if (std::abs(area) < 1e-14) continue;
    const double l1 = cross(c - b, p - b) / area, l2 = cross(a - c, p - c) / area, l3 = 1.0 - l1 - l2;
    if (l1 < 0.0 || l2 < 0.0 || l3 < 0.0) continue;
    return l1 * x[t[0]].y() + l2 * x[t[1]].y() + l3 * x[t[2]].y();
  }
  return std::numeric_limits<double>::quiet_NaN();
}

}  // namespace

namespace {

void pillows_rest_on_the_cloth(const std::string& method, const std::string& schedule);

}  // namespace

// XPBD passes since its contact projection is no longer held within the
// displacement bound (solver/self_contact_tasks.cpp); before, 14 pillow
// vertices ended 10.2 mm below the cloth beneath them.
TEST_CASE(
    "pillows rest on the cloth: every pillow vertex above the cloth beneath it, and the cloth sags under "
    "them (every method, single and heft)",
    "[contact][self][pillows]") {
  pillows_rest_on_the_cloth(GENERATE(from_range(test::methods_where(takes_pillows))), GENERATE("single", "heft"));
}

namespace {

void pillows_rest_on_the_cloth(const std::string& method, const std::string& schedule) {
  INFO(method << "/" << schedule);
  test::TempDir dir;
  app::RunOptions o;
  o.scene_path = std::string(ATSSIM_SOURCE_DIR) + "/scenes/pillows.yaml";
  o.overrides = small_pillows(dir, method, schedule, "with.h5", true);
  app::run_simulation(o);
  o.overrides = small_pillows(dir, method, "single", "without.h5", false);
  app::run_simulation(o);

  // The cloth's triangles only (its particles come first), as the grid is
  // cut (model/cloth_builder.cpp: diagonal b-c of each quad).
  Surface cloth;
  const int n = kPillowCloth;
  for (int k = 0; k + 1 < n; ++k) {
    for (int i = 0; i + 1 < n; ++i) {
      const int a = k * n + i, b = a + 1, c = a + n, d = c + 1;
      cloth.tris.push_back({a, c, b});
      cloth.tris.push_back({b, c, d});
    }
  }
  double lowest_margin = 1e9;  // pillow vertex height above the cloth beneath it
  int below = 0;
  for (int f = 0; f <= 50; ++f) {
    const std::vector<Vector3d> x = frame(dir.file("with.h5"), f);
    for (std::size_t i = n * n; i < x.size(); ++i) {
      REQUIRE(x[i].allFinite());
      const double h = cloth_height_below(cloth, x, x[i].x(), x[i].z());
      if (std::isnan(h)) continue;
      lowest_margin = std::min(lowest_margin, x[i].y() - h);
      below += x[i].y() < h;
    }
  }
  INFO("smallest pillow vertex height above the cloth: " << lowest_margin << " m");
  CHECK(below == 0);
  const auto lowest = [&](const std::string& file, std::size_t first, std::size_t last) {
    const std::vector<Vector3d> x = frame(dir.file(file), 50);
    double low = 1e9;
    for (std::size_t i = first; i < std::min(last, x.size()); ++i) low = std::min(low, x[i].y());
    return low;
  };
  const double pillows_low = lowest("with.h5", n * n, 1 << 30);
  const double cloth_with = lowest("with.h5", 0, n * n), cloth_without = lowest("without.h5", 0, n * n);
  INFO("cloth's lowest point: " << cloth_with << " m with the pillows on it, " << cloth_without << " m without");
  CHECK(pillows_low > 0.2);                  // on the cloth, not on the ground
  CHECK(cloth_with < cloth_without - 0.01);  // it sags under their weight
}

}  // namespace

TEST_CASE(
    "converge on two cloth layers resting on a sphere: y falls against the self-contact-aware Newton E*, at every "
    "doubling from k = 4 on (every descent method)",
    "[contact][self][converge]") {
  // 20 frames on, the layers lie on each other on the sphere; E* is the
  // minimum of the incremental potential with both contact energies in it
  // (the surface pairs found by brute force on the host). The sphere is
  // frictionless here: friction is no term of the potential, and its step
  // after the iterations moves the result off E* (with the scene's friction
  // 0.5 SOSD's y rose from 0.42 at k = 1 to 0.56 at k = 32).
  test::TempDir dir;
  std::string yaml = kLayers;
  yaml.replace(yaml.find("frames: 40"), 10, "frames: 20");
  yaml.replace(yaml.find(", friction: 0.5"), 15, "");
  const io::ConvergenceResult r =
      app::run_convergence(test::converge_options(dir, yaml + "solver: {method: vbd}\n", 64));
  test::check_ends_lower(r);
  for (const auto& t : r.traces) {
    INFO(t.variant);
    for (std::size_t i = 1; i < t.iterations.size(); ++i) {
      INFO("k = " << t.iterations[i - 1] << " -> " << t.iterations[i] << ": y = " << t.relative_error[i - 1] << " -> "
                  << t.relative_error[i]);
      if (t.iterations[i - 1] >= 4) CHECK(t.relative_error[i] <= t.relative_error[i - 1]);
    }
  }
  // Measured (k = 1 -> 64): VBD 0.24 -> 1.8e-5, JPGD 0.28 -> 6.1e-4, SOSD
  // 0.23 -> 3.8e-3, each falling at every doubling. Before, JPGD stalled at
  // 0.03 (Chebyshev's rho 0.9 with the pairs switching, now 0.7 with
  // surface contact; solver/jpgd/jpgd_method.cpp) and SOSD near 0.1, rising
  // between doublings (its pair blocks let both sides close the whole gap,
  // and its projection onto the colliders' surfaces after every iteration
  // kept it off the minimum; contact/self_contact_terms.h).
  REQUIRE(r.traces[0].variant.rfind("vbd", 0) == 0);
  CHECK(r.traces[0].relative_error.back() < 1e-3);
  CHECK(r.traces[1].relative_error.back() < 1e-2);
  CHECK(r.traces[2].relative_error.back() < 1e-2);
}

// The surface record of /contact (solver/contact/surface_contacts) on real
// output frames, against this file's own checker.
namespace {

// A sheet pinned where it is and a free one below it, which a rising sphere
// pushes up through it: the sphere's projection moves the free sheet past
// the contact, so the surfaces cross (from frame 13 under every method).
const char* kPushThrough =
    "simulation: {fps: 60, substeps: 8, iterations: 6, frames: 20, gravity: [0, 0, 0]}\n"
    "objects:\n"
    "  - {name: free, grid: {size: [0.4, 0.4], resolution: [8, 8]}, transform: {translate: [0, 0.15, 0]},\n"
    "     material: {density: 0.2, stretch_stiffness: 1000, bend_stiffness: 0.0001}}\n"
    "  - {name: fixed, grid: {size: [0.4, 0.4], resolution: [8, 8]},\n"
    "     transform: {rotate: [0, 30, 0], translate: [0.01, 0.2, 0.01]},\n"
    "     material: {density: 0.2, stretch_stiffness: 1000, bend_stiffness: 0.0001},\n"
    "     pins: {boxes: [{min: [-1, 0, -1], max: [1, 1, 1]}]}}\n"
    "colliders:\n"
    "  - {type: sphere, center: [0, -0.1, 0], radius: 0.1, thickness: 0.005, velocity: [0, 1, 0]}\n"
    "contact: {self: true, thickness: 0.01}\n";

// Per frame, the edge-triangle crossings this file's checker counts.
std::vector<int> crossings_per_frame(const Surface& s, const std::string& file, int frames) {
  std::vector<int> out;
  for (int f = 0; f <= frames; ++f) {
    SurfaceCheck c;
    check_frame(s, frame(file, f), f, c);
    out.push_back(c.crossings);
  }
  return out;
}

std::vector<int> as_ints(const std::vector<double>& v) { return std::vector<int>(v.begin(), v.end()); }

int count_lines(const std::string& text) { return static_cast<int>(std::count(text.begin(), text.end(), '\n')); }

}  // namespace

TEST_CASE(
    "the two layers' surface record: no crossing in any frame, as the checker finds, and the pairs and depth "
    "of its closest vertex-triangle pairs",
    "[contact][self][surface_record]") {
  test::TempDir dir;
  app::run_simulation(options(dir, kLayers, "vbd", "single"));
  const std::string out = dir.file("out.h5");
  const Surface s = surface_of(kLayers);
  const std::vector<int> crossings = as_ints(io::read_series(out, "/contact/surface_crossings"));
  const std::vector<double> pairs = io::read_series(out, "/contact/surface_pairs");
  const std::vector<double> depth = io::read_series(out, "/contact/surface_max_penetration");
  REQUIRE(crossings.size() == 41);
  CHECK(crossings == crossings_per_frame(s, out, 40));
  CHECK(crossings == std::vector<int>(41, 0));
  // The checker's vertex-triangle pairs within the thickness are some of
  // the record's pairs (which also hold the edge-edge ones), and the
  // deepest of them is at most as deep as the record's deepest.
  int frames_in_contact = 0;
  for (int f = 0; f <= 40; ++f) {
    const std::vector<Vector3d> x = frame(out, f);
    int within = 0;
    double closest = std::numeric_limits<double>::infinity();
    for (const auto& t : s.tris) {
      for (std::size_t v = 0; v < x.size(); ++v) {
        if (int(v) == t[0] || int(v) == t[1] || int(v) == t[2]) continue;
        const double d = point_triangle(x[v], x[t[0]], x[t[1]], x[t[2]]);
        if (d < kThickness) ++within, closest = std::min(closest, d);
      }
    }
    INFO("frame " << f << ": checker " << within << " pairs, closest " << closest << "; record " << pairs[f]
                  << " pairs, depth " << depth[f]);
    CHECK(pairs[f] >= within);
    if (within > 0) CHECK(depth[f] >= kThickness - closest - 1e-9);
    if (pairs[f] == 0) CHECK(depth[f] == 0.0);
    CHECK(depth[f] <= kThickness);
    frames_in_contact += within > 0;
  }
  CHECK(frames_in_contact > 0);  // the layers did meet
}

TEST_CASE(
    "surfaces pushed through each other: the record counts the checker's crossings, the run warns once on "
    "stderr, and with contact.strict ends with exit 1 keeping its frames, then resumes",
    "[contact][self][surface_record]") {
  test::TempDir dir;
  const std::string scene = dir.write("push.yaml", kPushThrough);
  const Surface s = surface_of(kPushThrough);
  const test::Outcome loose =
      test::run_atssim(dir, "run " + scene + " -o " + dir.file("loose.h5") + " --devices cpu/2 --json");
  INFO(loose.err);
  REQUIRE(loose.code == 0);
  const std::vector<int> crossings = as_ints(io::read_series(dir.file("loose.h5"), "/contact/surface_crossings"));
  REQUIRE(crossings.size() == 21);
  CHECK(crossings == crossings_per_frame(s, dir.file("loose.h5"), 20));
  const auto first = std::find_if(crossings.begin(), crossings.end(), [](int c) { return c > 0; });
  REQUIRE(first != crossings.end());
  const int crossed = static_cast<int>(first - crossings.begin());
  INFO("first crossing in frame " << crossed);
  CHECK(crossed > 0);  // they start apart
  // One warning line, naming that frame and its count; no error.
  CHECK(count_lines(loose.err) == 1);
  CHECK(loose.err.find(fmt::format("atssim: warning: surfaces crossed in frame {} ({} edge-triangle", crossed,
                                   crossings[crossed])) == 0);
  // The summary: the first crossing, and the last frame's record.
  CHECK(loose.out.find(fmt::format("\"first_crossing\": {}", crossed)) != std::string::npos);
  CHECK(loose.out.find(fmt::format("\"last\": {{\"frame\": 20, \"surface_pairs\": {}",
                                   io::read_series(dir.file("loose.h5"), "/contact/surface_pairs").back())) !=
        std::string::npos);
  const int most = *std::max_element(crossings.begin(), crossings.end());
  CHECK(loose.out.find(fmt::format("\"surface_crossings\": {}}}}}", most)) != std::string::npos);  // worst, last key

  // Strict: the run ends after writing the frame that crossed.
  const std::string strict_h5 = dir.file("strict.h5");
  const test::Outcome strict =
      test::run_atssim(dir, "run " + scene + " -o " + strict_h5 + " --devices cpu/2 --set contact.strict=true");
  INFO(strict.err);
  CHECK(strict.code == 1);
  CHECK(count_lines(strict.err) == 1);
  CHECK(strict.err.find(fmt::format("frame {}: surfaces crossed", crossed)) != std::string::npos);
  CHECK(strict.err.find("contact.strict") != std::string::npos);
  CHECK(strict.err.find(fmt::format("{} frames kept", crossed + 1)) != std::string::npos);
  const io::ResultSummary kept = io::read_summary(strict_h5);
  CHECK_FALSE(kept.complete);
  REQUIRE(kept.frames == static_cast<std::size_t>(crossed + 1));
  for (int f = 0; f <= crossed; ++f)
    CHECK(io::read_frame_positions(strict_h5, f) == io::read_frame_positions(dir.file("loose.h5"), f));
  // Resumed without strict (the scene's own setting): it goes on to the
  // end, as the uninterrupted run did, and warns again on its first frame.
  const test::Outcome resumed =
      test::run_atssim(dir, "run " + scene + " -o " + strict_h5 + " --devices cpu/2 --resume");
  INFO(resumed.err);
  CHECK(resumed.code == 0);
  CHECK(count_lines(resumed.err) == 1);
  CHECK(resumed.err.find(fmt::format("surfaces crossed in frame {}", crossed + 1)) != std::string::npos);
  CHECK(io::read_summary(strict_h5).complete);
  CHECK(as_ints(io::read_series(strict_h5, "/contact/surface_crossings")) == crossings);
  CHECK(io::read_frame_positions(strict_h5, 20) == io::read_frame_positions(dir.file("loose.h5"), 20));
}
