// Bending with a curved rest shape (issue #13): the dihedral model keeps any
// rest shape under every implicit method; the isometric one (flat rest only) does not.
#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

#include "app/simulation.hpp"
#include "io/result_reader.hpp"
#include "solver/method_registry.hpp"
#include "support/curved_meshes.hpp"
#include "support/methods.hpp"
#include "support/temp_dir.hpp"

using namespace atssim;

namespace {

// Float32 positions resolve 1.2e-7 m near 1 m from the origin: corrections
// that small are rounded to it, and over 100 frames a shell at rest 1 m up
// drifted 2e-5 to 1e-4 m under every method with or without bending; at the
// origin it stays within 2e-8 m. So the shells sit at the origin, and the
// falling cap starts 0.6 m up (it ends 0.64 m down).
std::string mesh_scene(const std::string& mesh, const std::string& gravity, int frames, const std::string& bend_model,
                       double y, double bend_stiffness, int substeps) {
  return "simulation: {fps: 60, substeps: " + std::to_string(substeps) +
         ", iterations: 8, frames: " + std::to_string(frames) + ", gravity: " + gravity +
         "}\n"
         "objects:\n"
         "  - name: shell\n"
         "    mesh: " +
         mesh +
         "\n"
         "    transform: {translate: [0, " +
         std::to_string(y) +
         ", 0]}\n"
         "    material: {density: 0.2, stretch_stiffness: " +
         (bend_stiffness > 0 ? "1000" : "0") + ", bend_stiffness: " + std::to_string(bend_stiffness) +
         ", bend_model: " + bend_model + "}\n";
}

struct Run {
  std::vector<std::vector<float>> frames;  // frame 0 = the initial state
};

// The methods that take a curved-mesh scene of these tests (an explicit
// method refuses one substep a frame: above its stable step).
std::vector<std::string> methods_taking_mesh(const test::ObjMesh& mesh, const std::string& gravity, double y) {
  test::TempDir dir;
  dir.write("mesh.obj", mesh.obj_text());
  return test::methods_taking(mesh_scene("mesh.obj", gravity, 1, "auto", y, 0.01, 1), {}, dir.path().string());
}

// bend_stiffness 0: no elastic element at all (free particles).
Run run(const test::TempDir& dir, const test::ObjMesh& mesh, const std::string& method, const std::string& gravity,
        int frames, const std::string& bend_model = "auto", double y = 0.0, double bend_stiffness = 0.01) {
  dir.write("mesh.obj", mesh.obj_text());
  app::RunOptions o;
  // One substep per frame keeps the test fast.
  o.scene_path = dir.write("scene.yaml", mesh_scene("mesh.obj", gravity, frames, bend_model, y, bend_stiffness, 1));
  o.overrides = {"output.path=" + dir.file("out.h5"), "devices=cpu", "solver.method=" + method};
  app::run_simulation(o);
  Run r;
  for (int f = 0; f <= frames; ++f) r.frames.push_back(io::read_frame_positions(dir.file("out.h5"), f));
  return r;
}

// The largest distance of any vertex from its initial position over all frames.
double largest_drift(const Run& r) {
  double worst = 0.0;
  const auto& rest = r.frames[0];
  for (const auto& x : r.frames) {
    for (std::size_t i = 0; i < rest.size(); i += 3) {
      const double dx = x[i] - rest[i], dy = x[i + 1] - rest[i + 1], dz = x[i + 2] - rest[i + 2];
      worst = std::max(worst, std::sqrt(dx * dx + dy * dy + dz * dz));
    }
  }
  return worst;
}

double mean_y(const std::vector<float>& x) {
  double s = 0.0;
  for (std::size_t i = 1; i < x.size(); i += 3) s += x[i];
  return s / static_cast<double>(x.size() / 3);
}

}  // namespace

// Every method but explicit integration: its stable step needs 26 (sphere)
// and 42 (cap) substeps a frame, and at 48 the shells drift 1.1e-6 and
// 1.4e-6 m in 100 frames (measured; nothing damps the rounding there).
TEST_CASE(
    "a closed sphere shell and an open spherical cap stay at rest within 5e-8 m without gravity, under every "
    "implicit method",
    "[bending][curved]") {
  const std::string method =
      GENERATE(from_range(test::method_names([](const solver::MethodDescription& m) { return m.name != "explicit"; })));
  const bool sphere = GENERATE(true, false);
  const test::ObjMesh mesh = sphere ? test::icosphere(0.3, 2) : test::spherical_cap(0.5, 0.3, 12);
  test::TempDir dir;
  const double drift = largest_drift(run(dir, mesh, method, "[0, 0, 0]", 100));
  INFO(method << (sphere ? " sphere" : " cap") << ": largest drift " << drift << " m in 100 frames");
  // Measured: xpbd 1.5e-8 / 3.7e-9 m (sphere / cap), vbd 1.7e-12 / 6.5e-9,
  // sosd 4.0e-10 / 4.7e-9, jpgd 1.7e-12 / 5.6e-9; a float32 ulp at the
  // shells' 0.3 m is 3e-8 m.
  CHECK(drift < 5e-8);
}

TEST_CASE("the isometric model does not keep a curved rest shape (the control of the test above)",
          "[bending][curved]") {
  test::TempDir dir;
  const double drift = largest_drift(run(dir, test::icosphere(0.3, 2), "xpbd", "[0, 0, 0]", 100, "isometric"));
  INFO("largest drift " << drift << " m");
  CHECK(drift > 1e-3);
}

TEST_CASE("a free-falling curved cap's centroid follows free fall, under every method at 8 iterations",
          "[bending][curved]") {
  const std::string method =
      GENERATE(from_range(methods_taking_mesh(test::spherical_cap(0.5, 0.3, 12), "[0, -9.81, 0]", 0.6)));
  test::TempDir dir;
  const test::ObjMesh cap = test::spherical_cap(0.5, 0.3, 12);
  const Run r = run(dir, cap, method, "[0, -9.81, 0]", 30, "auto", 0.6);
  // Every method steps the inertia as semi-implicit Euler (v += h g, x += h v
  // per substep), so after n substeps from rest a force-free body has fallen
  // g h² n (n + 1) / 2 exactly.
  const double h = 1.0 / 60.0;
  const int n = 30;
  const double fall = 9.81 * h * h * n * (n + 1) / 2.0;
  const double fell = mean_y(r.frames[0]) - mean_y(r.frames[30]);
  // The same particles with no element at all: what float32 leaves of free fall.
  const Run free = run(dir, cap, method, "[0, -9.81, 0]", 30, "auto", 0.6, 0.0);
  const double free_fell = mean_y(free.frames[0]) - mean_y(free.frames[30]);
  INFO(method << ": centroid fell " << fell << " m, free fall " << fall << " m, free particles " << free_fell << " m");
  CHECK(std::abs(fell - fall) < 1e-4);
  CHECK(std::abs(fell - free_fell) < 1e-4);  // measured: XPBD 3e-5, the others below 1e-5
}
