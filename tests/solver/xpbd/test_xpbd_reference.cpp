#include <catch2/catch.hpp>

#include "model/cloth_builder.hpp"
#include "scene/scene_loader.hpp"
#include "solver/xpbd/xpbd_reference.hpp"
#include "support/scenes.hpp"

using namespace atssim;
using namespace atssim::solver;
using namespace atssim::solver::xpbd;

namespace {

model::Model free_particles() {
  // No stiffness given: no element sets, just particles under gravity.
  const std::string yaml =
      "simulation: {gravity: [0.5, -9.81, 0.25]}\n"
      "objects:\n  - grid: {size: [0.01, 0.01], resolution: [3, 3]}\n";
  return model::build_model(scene::parse_scene(yaml, "s.yaml", "."));
}

}  // namespace

TEST_CASE("without constraints the host XPBD reproduces discrete free fall exactly") {
  const model::Model m = free_particles();
  const double h = 1.0 / 960.0;
  XpbdReference ref(make_sim_layout(m), {h, 4});
  const int n = 16;
  for (int s = 0; s < n; ++s) ref.substep();
  // Semi-implicit Euler: v_k = v0 + k h g, x_n = x0 + h * sum v_k = x0 + h^2 g n(n+1)/2.
  const double k = h * h * n * (n + 1) / 2.0;
  for (std::size_t i = 0; i < m.particles.size(); ++i) {
    const auto& x = ref.state().x[i];
    CHECK(x.x == Approx(m.particles.position[i].x() + k * 0.5).margin(1e-6));
    CHECK(x.y == Approx(m.particles.position[i].y() + k * -9.81).margin(1e-6));
    CHECK(x.z == Approx(m.particles.position[i].z() + k * 0.25).margin(1e-6));
  }
}

TEST_CASE("the hanging cloth's XPBD residual falls as iterations rise") {
  const auto m = model::build_model(scene::parse_scene(test::hanging_cloth_yaml(12, 1e3, 1e-3), "s.yaml", "."));
  double previous = 1e30;
  for (int iterations : {1, 2, 4, 8, 16, 32}) {
    XpbdReference ref(make_sim_layout(m), {1.0 / 240.0, iterations});
    // A few substeps first, so the cloth is moving and stretched.
    for (int s = 0; s < 5; ++s) ref.substep();
    const double r = ref.residual_rms();
    INFO("iterations " << iterations << " residual " << r);
    CHECK(r < previous);
    previous = r;
  }
}

TEST_CASE("pinned particles never move in the host reference") {
  const auto m = model::build_model(scene::parse_scene(test::hanging_cloth_yaml(8), "s.yaml", "."));
  XpbdReference ref(make_sim_layout(m), {1.0 / 240.0, 8});
  for (int s = 0; s < 20; ++s) ref.substep();
  for (std::size_t i = 0; i < m.particles.size(); ++i) {
    if (m.particles.inv_mass[i] != 0.0) continue;
    CHECK(ref.state().x[i].x == float(m.particles.position[i].x()));
    CHECK(ref.state().x[i].y == float(m.particles.position[i].y()));
    CHECK(ref.state().x[i].z == float(m.particles.position[i].z()));
  }
}

TEST_CASE("a stiff stretched spring is restored to its rest length") {
  // Two particles, one pinned, one pulled 10% too far: with compliance 0 a
  // single XPBD iteration restores the rest length.
  model::Model m;
  m.gravity = model::Vec3::Zero();
  m.particles.position = {model::Vec3(0, 0, 0), model::Vec3(1.1, 0, 0)};
  m.particles.velocity = {model::Vec3::Zero(), model::Vec3::Zero()};
  m.particles.mass = {1.0, 1.0};
  m.particles.inv_mass = {0.0, 1.0};
  m.stretch.edges = {{0, 1}};
  m.stretch.rest_length = {1.0};
  m.stretch.compliance = {0.0};
  XpbdReference ref(make_sim_layout(m), {0.01, 1});
  ref.substep();
  CHECK(ref.state().x[1].x == Approx(1.0).margin(1e-6));
  CHECK(ref.state().x[0].x == 0.0f);
}
