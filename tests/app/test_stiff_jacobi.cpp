// The Jacobi methods on stiff scenes (solver/vertex/stiffness_ratio.hpp):
// issue #13's cloth of density 1e-6 kg/m² at stiffness 1e12 and the other
// stiff cells that made SOSD and JPGD move a pinned cloth up or far beyond
// free fall. Reference: a cloth pinned at two corners under gravity, at
// rest at first, cannot lower its centre of mass faster than free fall
// (the pins only hold it up), and it must lower it.
#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

#include <fmt/format.h>

#include "app/simulation.hpp"
#include "io/result_reader.hpp"
#include "support/methods.hpp"
#include "support/temp_dir.hpp"

using namespace atssim;

namespace {

std::string pinned_cloth(double density, double stiffness) {
  return fmt::format(
      "simulation: {{fps: 60, substeps: 16, iterations: 8, frames: 10}}\n"
      "objects:\n"
      "  - grid: {{size: [1.0, 1.0], resolution: [16, 16]}}\n"
      "    transform: {{translate: [0, 1.5, 0]}}\n"
      "    material: {{density: {}, stretch_stiffness: {}, bend_stiffness: 0.001}}\n"
      "    pins: {{boxes: [{{min: [-0.51, 1.49, -0.51], max: [-0.49, 1.51, -0.49]}},\n"
      "                   {{min: [0.49, 1.49, -0.51], max: [0.51, 1.51, -0.49]}}]}}\n",
      density, stiffness);
}

// A number the method picks from the scene (MethodOption::depends_on_scene:
// a safer value on stiff scenes): SOSD's stencil step, JPGD's Chebyshev rho.
// A named option picked from the scene (XPBD's ordering, by size) is a
// choice of speed, not of safety.
bool picked_for_safety(const solver::MethodOption& o) { return o.depends_on_scene && o.choices.empty(); }

// The methods that pick such an option.
bool picks_from_scene(const solver::MethodDescription& m) {
  return std::any_of(m.options.begin(), m.options.end(), picked_for_safety);
}

// Those options set by the scene to their usual (aggressive) values.
std::vector<std::string> usual_values(const std::string& method) {
  std::vector<std::string> out;
  for (const solver::MethodOption& o : solver::method(method).options) {
    if (picked_for_safety(o)) out.push_back(fmt::format("solver.{}={}", o.key, o.default_text()));
  }
  return out;
}

double centroid_y(const std::string& file, std::size_t frame) {
  const std::vector<float> xyz = io::read_frame_positions(file, frame);
  double sum = 0.0;
  for (std::size_t i = 1; i < xyz.size(); i += 3) sum += xyz[i];
  const std::size_t points = xyz.size() / 3;
  return sum / static_cast<double>(points);
}

}  // namespace

TEST_CASE(
    "on stiff scenes the methods that pick their options from the scene lower a pinned cloth, never faster "
    "than free fall",
    "[methods][stiff]") {
  const std::string method = GENERATE(from_range(test::methods_where(picks_from_scene)));  // SOSD, JPGD
  const auto cell = GENERATE(std::pair{1e-6, 1e12}, std::pair{1e-6, 1e8}, std::pair{1e-4, 1e8}, std::pair{1e-4, 1e12},
                             std::pair{0.01, 1e8}, std::pair{0.01, 1e12}, std::pair{0.2, 1e12});
  INFO(method << ": density " << cell.first << " kg/m², stiffness " << cell.second << " N/m");
  test::TempDir dir;
  app::RunOptions o;
  o.scene_path = dir.write("scene.yaml", pinned_cloth(cell.first, cell.second));
  o.overrides = {"output.path=" + dir.file("out.h5"), "devices=cpu/2:0", "solver.method=" + method};
  app::run_simulation(o);
  const double drop = centroid_y(dir.file("out.h5"), 0) - centroid_y(dir.file("out.h5"), 10);
  const double t = 10.0 / 60.0, free_fall = 0.5 * 9.81 * t * t;
  INFO("centroid drop " << drop << " m, free fall " << free_fall << " m");
  CHECK(drop > 0.0);
  CHECK(drop <= free_fall);
}

TEST_CASE("a stencil step or Chebyshev rho the scene sets is kept on a stiff scene", "[methods][stiff]") {
  // The aggressive values, asked for: the run takes them (and, here, the
  // cloth rises or overshoots free fall, as before the safe defaults).
  const std::string method = GENERATE(from_range(test::methods_where(picks_from_scene)));
  test::TempDir dir;
  app::RunOptions o;
  o.scene_path = dir.write("scene.yaml", pinned_cloth(0.2, 1e12));
  o.overrides = {"output.path=" + dir.file("out.h5"), "devices=cpu/2:0", "solver.method=" + method};
  for (const std::string& set : usual_values(method)) o.overrides.push_back(set);  // stencil_step 0.7, rho 0.9
  app::run_simulation(o);
  const double drop = centroid_y(dir.file("out.h5"), 0) - centroid_y(dir.file("out.h5"), 10);
  const double t = 10.0 / 60.0, free_fall = 0.5 * 9.81 * t * t;
  INFO(method << ": centroid drop " << drop << " m, free fall " << free_fall << " m");
  CHECK((drop < 0.0 || drop > free_fall));
}
