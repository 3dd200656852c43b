#include <catch2/catch.hpp>

#include <cmath>
#include <string>
#include <tuple>
#include <utility>
#include <vector>

#include <fmt/format.h>

#include "app/simulation.hpp"
#include "io/result_reader.hpp"
#include "support/methods.hpp"
#include "support/temp_dir.hpp"

using namespace atssim;

namespace {

// A 1 m bar of 0.1 × 0.1 m section, 8 cells long, hanging from its top face.
const char* kBar =
    "simulation: {fps: 60, substeps: 4, iterations: 100, frames: 30, gravity: [0, -9.81, 0]}\n"
    "objects:\n"
    "  - name: bar\n"
    "    type: solid\n"
    "    box: {size: [0.1, 1.0, 0.1], resolution: [1, 8, 1]}\n"
    "    material: {density: 1000, youngs_modulus: 1.0e7, poisson_ratio: 0.0, model: neo_hookean}\n"
    "    pins:\n"
    "      boxes:\n"
    "        - {min: [-1, 0.49, -1], max: [1, 0.51, 1]}\n";

}  // namespace

TEST_CASE("a bar hanging under its own weight stretches by rho g L^2 / (2E) (every method on tetrahedra)") {
  // XPBD solves StVK (its strain constraints minimise that energy); at this
  // small strain StVK and neo-Hookean are both linear elasticity. The
  // tolerance is what README.md claims per method.
  const auto [method, iterations, material, tolerance] =
      GENERATE(std::make_tuple(std::string("vbd"), 100, std::string("neo_hookean"), 0.05),
               std::make_tuple(std::string("sosd"), 200, std::string("neo_hookean"), 0.05),
               std::make_tuple(std::string("jpgd"), 300, std::string("neo_hookean"), 0.05),
               std::make_tuple(std::string("xpbd"), 100, std::string("stvk"), 0.01));
  test::TempDir dir;
  app::RunOptions o;
  o.scene_path = dir.write("bar.yaml", kBar);
  o.overrides = {"output.path=" + dir.file("bar.h5"), "devices=cpu", "solver.method=" + method,
                 "simulation.iterations=" + std::to_string(iterations), "objects.0.material.model=" + material};
  app::run_simulation(o);
  if (method == "xpbd") {
    // split and heft on the two sub-devices write the one-device bits
    // (checked over the first 3 frames), so the bound below holds for them.
    // Async is another iteration, placed by profiled costs: not claimed.
    for (const std::string schedule : {"split", "heft"}) {
      INFO(schedule);
      app::RunOptions two = o;
      two.overrides = {"output.path=" + dir.file(schedule + ".h5"),
                       "devices=cpu/2",
                       "solver.method=xpbd",
                       "simulation.iterations=100",
                       "objects.0.material.model=stvk",
                       "simulation.frames=3",
                       "solver.schedule=" + schedule};
      app::run_simulation(two);
      for (std::size_t f = 1; f <= 3; ++f) {
        CHECK(io::read_frame_positions(dir.file(schedule + ".h5"), f) ==
              io::read_frame_positions(dir.file("bar.h5"), f));
      }
    }
  }
  const auto rest = io::read_frame_positions(dir.file("bar.h5"), 0);
  // Undamped, the bar oscillates about its static equilibrium (period
  // 4 L / sqrt(E / rho) = 0.04 s): 30 frames at 60 Hz sample 12 periods at
  // 5 evenly spaced phases, so their mean is the equilibrium.
  double sum = 0.0;
  int samples = 0;
  for (std::size_t f = 1; f <= 30; ++f) {
    const auto x = io::read_frame_positions(dir.file("bar.h5"), f);
    for (std::size_t i = 0; i < rest.size() / 3; ++i) {
      if (rest[3 * i + 1] > -0.49f) continue;  // bottom face
      REQUIRE(std::isfinite(x[3 * i + 1]));
      sum += x[3 * i + 1] - rest[3 * i + 1];
      ++samples;
    }
  }
  const double tip = sum / samples;
  const double analytic = -1000.0 * 9.81 * 1.0 / (2.0 * 1.0e7);  // linear elasticity, nu = 0
  INFO(method << ": mean tip displacement " << tip << " m, analytic " << analytic << " m");
  CHECK(tip == Approx(analytic).epsilon(tolerance));  // measured: vbd 2.2 %, sosd 3.1 %, jpgd 1.6 %, xpbd 0.97 %
}

namespace {

// A cloth 1.5 m up on a ground at 1.2 m: after 20 frames it has hit it.
// The explicit method takes 32 substeps (its stable step), the others 4.
std::string ground_cloth(const std::string& method) {
  return std::string("simulation: {fps: 60, substeps: ") + (method == "explicit" ? "32" : "4") +
         ", iterations: 8, frames: 20, ground: 1.2}\n"
         "objects:\n"
         "  - grid: {size: [1, 1], resolution: [12, 12]}\n"
         "    transform: {translate: [0, 1.5, 0]}\n"
         "    material: {density: 0.2, stretch_stiffness: 1000, bend_stiffness: 0.001}\n"
         "    pins: {vertices: [0]}\n";
}

// Every method that takes the scene under every schedule it runs (async:
// the Gauss-Seidel ones), as README.md claims for the ground task.
std::vector<std::pair<std::string, std::string>> ground_cases() {
  std::vector<std::pair<std::string, std::string>> out;
  for (const std::string& m : test::methods_taking(ground_cloth)) {
    for (const char* s : {"single", "split", "heft", "async"}) {
      if (std::string(s) != "async" || solver::method(m).gauss_seidel) out.emplace_back(m, s);
    }
  }
  return out;
}

}  // namespace

TEST_CASE("no particle ends below the ground plane, under every method and schedule") {
  const auto [method, schedule] = GENERATE(from_range(ground_cases()));
  test::TempDir dir;
  const std::string yaml = ground_cloth(method);
  app::RunOptions o;
  o.scene_path = dir.write("ground.yaml", yaml);
  o.overrides = {"output.path=" + dir.file("g.h5"), "devices=cpu/2", "solver.method=" + method,
                 "solver.schedule=" + schedule};
  app::run_simulation(o);
  double lowest = 1e9;
  for (std::size_t f = 0; f <= 20; ++f) {
    const auto x = io::read_frame_positions(dir.file("g.h5"), f);
    for (std::size_t i = 1; i < x.size(); i += 3) lowest = std::min(lowest, double(x[i]));
  }
  INFO(method << "/" << schedule);
  CHECK(lowest >= 1.2 - 1e-6);
  CHECK(lowest <= 1.2 + 1e-6);  // and it did reach the ground
}

TEST_CASE("pillows: cloth and tetrahedra in one substep graph on two devices, and the pillows land on the ground") {
  test::TempDir dir;
  app::RunOptions o;
  o.scene_path = std::string(ATSSIM_SOURCE_DIR) + "/scenes/pillows.yaml";
  o.overrides = {"output.path=" + dir.file("p.h5"), "devices=cpu/2", "solver.schedule=heft", "simulation.frames=40",
                 "contact.self=false"};  // without cloth-solid contact (tests/app/test_self_contact.cpp has it)
  app::run_simulation(o);
  const std::size_t cloth = 32 * 32;  // the cloth's particles come first
  double pillow_low = 1e9, cloth_low = 1e9;
  for (std::size_t f = 0; f <= 40; ++f) {
    const auto x = io::read_frame_positions(dir.file("p.h5"), f);
    REQUIRE(x.size() > 3 * cloth);
    for (std::size_t i = 0; i < x.size() / 3; ++i) {
      REQUIRE(std::isfinite(x[3 * i]));
      REQUIRE(std::isfinite(x[3 * i + 1]));
      REQUIRE(std::isfinite(x[3 * i + 2]));
      double& low = i < cloth ? cloth_low : pillow_low;
      low = std::min(low, double(x[3 * i + 1]));
    }
  }
  // Free fall from 1.2 m takes 0.49 s (30 frames): by frame 40 they have hit
  // the ground (and, undamped, bounce), never going below it.
  CHECK(pillow_low == Approx(0.0).margin(1e-6));
  // The cloth hangs from its corners at 0.8 m: it sags, without reaching the ground.
  CHECK(cloth_low < 0.8);
  CHECK(cloth_low > 0.3);
}

namespace {

// The bundled soft box as StVK under XPBD, on two sub-devices, with the
// given changes.
std::string run_soft_box(const test::TempDir& dir, const std::string& schedule, int frames, int resolution,
                         std::vector<std::string> overrides = {}) {
  app::RunOptions o;
  o.scene_path = std::string(ATSSIM_SOURCE_DIR) + "/scenes/soft_box.yaml";
  const std::string out = dir.file(schedule + ".h5");
  overrides.insert(overrides.end(),
                   {"output.path=" + out, "devices=cpu/2", "solver.method=xpbd", "objects.0.material.model=stvk",
                    fmt::format("objects.0.box.resolution=[{0}, {0}, {0}]", resolution),
                    "simulation.frames=" + std::to_string(frames), "solver.schedule=" + schedule});
  o.overrides = overrides;
  app::run_simulation(o);
  return out;
}

}  // namespace

TEST_CASE("split and heft give the single-device XPBD solid bit for bit") {
  // 1296 tets, so that the tet color blocks are big enough to be cut between
  // the devices (plan_split's granule is 64); dropped from 0.35 m so that it
  // lands within the 12 frames; few substeps and iterations to keep it short.
  const std::vector<std::string> quick = {"simulation.substeps=4", "simulation.iterations=4",
                                          "objects.0.transform.translate=[0, 0.35, 0]"};
  test::TempDir dir;
  const int frames = 12;
  const auto single = io::read_frame_positions(run_soft_box(dir, "single", frames, 6, quick), frames);
  double lowest = 1e9;
  for (std::size_t i = 1; i < single.size(); i += 3) lowest = std::min(lowest, double(single[i]));
  CHECK(lowest < 1e-6);  // it has landed
  for (const std::string schedule : {"split", "heft"}) {
    const auto two = io::read_frame_positions(run_soft_box(dir, schedule, frames, 6, quick), frames);
    REQUIRE(two.size() == single.size());
    double worst = 0.0;
    for (std::size_t i = 0; i < two.size(); ++i) worst = std::max(worst, double(std::abs(two[i] - single[i])));
    INFO(schedule << ": max |difference| " << worst);
    CHECK(two == single);
  }
}

TEST_CASE("async XPBD drops the StVK soft box onto the ground without NaN") {
  test::TempDir dir;
  const int frames = 30;
  // At resolution 5 the async placement uses both sub-devices (at 4 it
  // keeps the small box on one).
  const std::string out = run_soft_box(dir, "async", frames, 5);
  double lowest = 1e9, highest = -1e9;
  for (std::size_t f = 0; f <= std::size_t(frames); ++f) {
    const auto x = io::read_frame_positions(out, f);
    for (std::size_t i = 1; i < x.size(); i += 3) {
      REQUIRE(std::isfinite(x[i - 1]));
      REQUIRE(std::isfinite(x[i]));
      REQUIRE(std::isfinite(x[i + 1]));
      lowest = std::min(lowest, double(x[i]));
      if (f == std::size_t(frames)) highest = std::max(highest, double(x[i]));
    }
  }
  INFO("lowest y " << lowest << ", top of the box at the end " << highest);
  CHECK(lowest >= -1e-6);  // every particle stays above the ground y = 0
  CHECK(lowest <= 1e-6);   // and the box did reach it
  CHECK(highest > 0.1);    // squashed by the landing (as under VBD), not flattened
}
