// Blow-up by energy (app/energy_growth.hpp): the energies against sums
// worked out by hand, the stretched cloth that the displacement check lets
// through, free fall that must not trip it, and every bundled scene run a
// few frames without tripping it.
#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <string>
#include <vector>

#include "app/blow_up.hpp"
#include "app/energy_growth.hpp"
#include "app/simulation.hpp"
#include "model/cloth_builder.hpp"
#include "scene/scene_loader.hpp"
#include "solver/layout/sim_layout.hpp"
#include "support/temp_dir.hpp"

using namespace atssim;

namespace {

// A `size` m square cloth of 8 x 8 vertices, pinned at two corners of its
// first row (stretch springs only, no bending).
std::string cloth_yaml(double size, double gravity) {
  return "simulation: {fps: 60, substeps: 16, gravity: [0, " + std::to_string(gravity) +
         ", 0]}\n"
         "objects:\n"
         "  - name: sail\n"
         "    grid: {size: [" +
         std::to_string(size) + ", " + std::to_string(size) +
         "], resolution: [8, 8]}\n"
         "    material: {density: 0.2, stretch_stiffness: 1.0e4}\n"
         "    pins: {vertices: [0, 7]}\n";
}

struct Cloth {
  model::Model model;
  solver::SimLayout layout;
  std::vector<float> xyz, zero_v;
};

Cloth cloth(double size, double gravity) {
  Cloth c;
  c.model = model::build_model(scene::parse_scene(cloth_yaml(size, gravity), "cloth.yaml", "."));
  c.layout = solver::make_sim_layout(c.model);
  for (const solver::Float4& p : c.layout.x) c.xyz.insert(c.xyz.end(), {p.x, p.y, p.z});
  c.zero_v.assign(c.xyz.size(), 0.0f);
  return c;
}

double spring_energy(const Cloth& c, const std::vector<float>& xyz) {
  double sum = 0.0;
  for (const ats_distance_c& s : c.layout.stretch) {
    const double d = std::hypot(xyz[3 * s.a] - xyz[3 * s.b], xyz[3 * s.a + 1] - xyz[3 * s.b + 1],
                                xyz[3 * s.a + 2] - xyz[3 * s.b + 2]);
    sum += 0.5 / s.compliance * (d - s.rest) * (d - s.rest);
  }
  return sum;
}

}  // namespace

TEST_CASE("the energy of a state is 1/2 m v^2 of the free particles plus 1/2 k (l - l0)^2 of the springs", "[fast]") {
  Cloth c = cloth(1.0, -9.81);
  const app::EnergyGrowthCheck check(c.layout, c.zero_v, c.model.objects, 1000.0);
  REQUIRE(check.energy(c.xyz, c.zero_v).total() < 1e-8);  // at rest, unstretched (float rest lengths)

  std::vector<float> v(c.xyz.size(), 0.0f), x = c.xyz;
  double kinetic = 0.0;
  for (std::size_t i = 0; i < c.layout.x.size(); ++i) {
    v[3 * i + 1] = 2.0f;  // 2 m/s up, pinned ones included (no mass: no energy)
    if (c.layout.x[i].w > 0.0f) kinetic += 0.5 * (1.0 / c.layout.x[i].w) * 4.0;
  }
  x[3 * 20 + 0] += 0.05f;  // vertex 20 pulled 5 cm along x
  const auto e = check.energy(x, v);
  CHECK(e.kinetic == Approx(kinetic).epsilon(1e-6));
  CHECK(e.elastic == Approx(spring_energy(c, x)).epsilon(1e-5));
  CHECK(e.elastic > 0.0);
}

TEST_CASE("a pinned cloth stretched 1e5 m in one frame passes the displacement check and trips the energy check",
          "[fast]") {
  // A 1 km sail: its size lets a particle move 10 x 1.4 km per substep, so
  // pulling its free edge 1e5 m down in one frame passes the displacement check.
  Cloth c = cloth(1000.0, -9.81);
  std::vector<float> stretched = c.xyz;
  for (std::size_t i = 56; i < 64; ++i) stretched[3 * i + 1] -= 1.0e5f;  // the last row of the 8 x 8 grid
  const app::BlowUpBounds bounds = app::blow_up_bounds(c.xyz, c.zero_v, 9.81, 1.0 / 60.0, 16);
  REQUIRE_FALSE(app::find_blow_up(c.xyz, stretched, bounds, 1.0 / 60.0, 1));

  app::EnergyGrowthCheck check(c.layout, c.zero_v, c.model.objects, 1000.0);
  const auto before = check.energy(c.xyz, c.zero_v);
  const auto after = check.energy(stretched, c.zero_v);
  const auto why = check.check(before, c.xyz, after, stretched);
  REQUIRE(why);
  INFO(*why);
  CHECK(why->find("object 'sail'") != std::string::npos);
  // The element that exploded first is a spring into the moved row (vertices 56 ... 63).
  CHECK(why->find("the stretch element between vertices") != std::string::npos);
  CHECK(why->find("energy_growth_limit") != std::string::npos);
  CHECK(check.largest_growth() > 1000.0);

  // Off (limit 0): the same frame passes.
  app::EnergyGrowthCheck off(c.layout, c.zero_v, c.model.objects, 0.0);
  CHECK_FALSE(off.check(off.energy(c.xyz, c.zero_v), c.xyz, off.energy(stretched, c.zero_v), stretched));
}

TEST_CASE("free fall under strong gravity is work done by gravity, not a blow-up", "[fast]") {
  // No pins: every particle falls g t^2 / 2 in a 10 s frame under g = 1e5
  // m/s^2 and ends at g t: its kinetic energy is exactly gravity's work.
  Cloth c = cloth(1.0, -1.0e5);
  for (solver::Float4& p : c.layout.x) p.w = c.layout.x[2].w;  // unpin: every particle free
  std::vector<float> fallen = c.xyz, v(c.xyz.size(), 0.0f);
  for (std::size_t i = 0; i < c.layout.x.size(); ++i) {
    fallen[3 * i + 1] -= 0.5f * 1.0e5f * 100.0f;
    v[3 * i + 1] = -1.0e5f * 10.0f;
  }
  app::EnergyGrowthCheck check(c.layout, c.zero_v, c.model.objects, 1000.0);
  const auto before = check.energy(c.xyz, c.zero_v);
  const auto after = check.energy(fallen, v);
  CHECK(after.kinetic > 1e9);
  const auto why = check.check(before, c.xyz, after, fallen);
  INFO((why ? *why : std::string("no blow-up")));
  CHECK_FALSE(why);
  // 0 but for float rounding of a 5e6 m fall: far below the scale, let alone 1000 of it.
  CHECK(std::abs(check.largest_growth()) < 1.0);
}

TEST_CASE("no bundled scene trips the energy check in its first frames") {
  std::vector<std::filesystem::path> scenes;
  for (const auto* folder : {"/scenes", "/scenes/paper"}) {
    for (const auto& entry : std::filesystem::directory_iterator(std::string(ATSSIM_SOURCE_DIR) + folder)) {
      const std::string name = entry.path().filename().string();
      const bool paper = std::string(folder) == "/scenes/paper";
      if (entry.path().extension() == ".yaml" && (!paper || name.find("_small.yaml") != std::string::npos)) {
        scenes.push_back(entry.path());
      }
    }
  }
  std::sort(scenes.begin(), scenes.end());
  REQUIRE(scenes.size() >= 12);
  for (const auto& path : scenes) {
    test::TempDir dir;
    app::RunOptions o;
    o.scene_path = path.string();
    // Two frames; the paper's scenes with 4 substeps (their contact starts
    // within the first frames, tests/app/test_paper_scenes.cpp).
    o.overrides = {"output.path=" + dir.file("out.h5"), "simulation.frames=2", "devices=cpu"};
    if (path.parent_path().filename() == "paper") o.overrides.push_back("simulation.substeps=4");
    INFO(path.filename().string());
    app::RunResult r;
    CHECK_NOTHROW(app::run_simulation(o, r));
    CHECK(r.frames_simulated == 2);
    CHECK(std::isfinite(r.energy_growth));
    CHECK(r.energy_growth < 1000.0);
    WARN(path.filename().string() << ": largest energy growth " << r.energy_growth << " of the 1000 allowed");
  }
}
