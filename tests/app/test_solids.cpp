#include <catch2/catch.hpp>

#include <cmath>

#include "app/simulation.hpp"
#include "io/result_reader.hpp"
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

TEST_CASE("a bar hanging under its own weight stretches by rho g L^2 / (2E) (VBD, SOSD and JPGD on tetrahedra)") {
  const auto [method, iterations] =
      GENERATE(std::make_pair(std::string("vbd"), 100), std::make_pair(std::string("sosd"), 200),
               std::make_pair(std::string("jpgd"), 300));
  test::TempDir dir;
  app::RunOptions o;
  o.scene_path = dir.write("bar.yaml", kBar);
  o.overrides = {"output.path=" + dir.file("bar.h5"), "devices=cpu", "solver.method=" + method,
                 "simulation.iterations=" + std::to_string(iterations)};
  app::run_simulation(o);
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
  CHECK(tip == Approx(analytic).epsilon(0.05));
}

TEST_CASE("no particle ends below the ground plane, whatever the method and schedule") {
  const auto [method, schedule] = GENERATE(std::make_pair(std::string("xpbd"), std::string("single")),
                                           std::make_pair(std::string("xpbd"), std::string("async")),
                                           std::make_pair(std::string("vbd"), std::string("heft")),
                                           std::make_pair(std::string("sosd"), std::string("heft")),
                                           std::make_pair(std::string("jpgd"), std::string("split")));
  test::TempDir dir;
  // A cloth 1.5 m up on a ground at 1.2 m: after 20 frames it has hit it.
  const std::string yaml =
      "simulation: {fps: 60, substeps: 4, iterations: 8, frames: 20, ground: 1.2}\n"
      "objects:\n"
      "  - grid: {size: [1, 1], resolution: [12, 12]}\n"
      "    transform: {translate: [0, 1.5, 0]}\n"
      "    material: {density: 0.2, stretch_stiffness: 1000, bend_stiffness: 0.001}\n"
      "    pins: {vertices: [0]}\n";
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
  o.overrides = {"output.path=" + dir.file("p.h5"), "devices=cpu/2", "solver.schedule=heft", "simulation.frames=40"};
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
