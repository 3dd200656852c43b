#include <catch2/catch.hpp>

#include <cmath>
#include <cstring>

#include "model/cloth_builder.hpp"
#include "scene/scene_loader.hpp"
#include "solver/energy/incremental_potential.hpp"
#include "solver/energy/moving_cloth.hpp"
#include "solver/newton/newton_reference.hpp"
#include "solver/vbd/vbd_reference.hpp"
#include "support/scenes.hpp"
#include "util/error.hpp"

using namespace atssim;
using namespace atssim::solver;
using namespace atssim::solver::vbd;

namespace {

constexpr double kH = 1.0 / 240.0;

bool same_bits(const std::vector<Float4>& a, const std::vector<Float4>& b) {
  return a.size() == b.size() && std::memcmp(a.data(), b.data(), a.size() * sizeof(Float4)) == 0;
}

// Five substeps of a and b from `start`: the same bits, and they moved.
void check_same_substeps(VbdReference a, VbdReference b, const SimLayout& start) {
  for (int s = 0; s < 5; ++s) {
    a.substep();
    b.substep();
  }
  CHECK(same_bits(a.state().x, b.state().x));
  CHECK(same_bits(a.state().v, b.state().v));
  CHECK_FALSE(same_bits(a.state().x, start.x));
}

// The moving cloth with a ground just below its lowest particle, so that
// some vertices take the bounded step.
SimLayout moving_cloth_over_ground() {
  SimLayout layout = test::moving_cloth(16, 1e4, 1e-3, kH);
  float lowest = layout.x.front().y;
  for (const Float4& p : layout.x) lowest = std::min(lowest, p.y);
  layout.has_ground = true;
  layout.ground_y = lowest + 2e-3f;
  return layout;
}

}  // namespace

TEST_CASE("without elements the host VBD reproduces discrete free fall exactly", "[vbd]") {
  const std::string yaml =
      "simulation: {gravity: [0.5, -9.81, 0.25]}\n"
      "objects:\n  - grid: {size: [0.01, 0.01], resolution: [3, 3]}\n";
  const model::Model m = model::build_model(scene::parse_scene(yaml, "s.yaml", "."));
  const double h = 1.0 / 960.0;
  VbdReference ref(make_sim_layout(m), h, 4);
  const int n = 16;
  for (int s = 0; s < n; ++s) ref.substep();
  // No force but gravity: each vertex stays at its inertia target x~.
  const double k = h * h * n * (n + 1) / 2.0;
  for (std::size_t i = 0; i < m.particles.size(); ++i) {
    const auto& x = ref.state().x[i];
    CHECK(x.x == Approx(m.particles.position[i].x() + k * 0.5).margin(1e-6));
    CHECK(x.y == Approx(m.particles.position[i].y() + k * -9.81).margin(1e-6));
    CHECK(x.z == Approx(m.particles.position[i].z() + k * 0.25).margin(1e-6));
  }
}

TEST_CASE("a host VBD substep lowers the incremental potential below its value at the predicted positions", "[vbd]") {
  const SimLayout start = test::moving_cloth(16, 1e4, 1e-3, kH);
  VbdReference ref(start, kH, 8);
  ref.substep();
  SimLayout at_prediction = ref.state();
  at_prediction.x = ref.predicted();
  const double e0 = energy::incremental_potential(at_prediction, ref.predicted(), kH);
  const double e = energy::incremental_potential(ref.state(), ref.predicted(), kH);
  INFO("E(x~) " << e0 << " E(x) " << e);
  CHECK(e < e0);
  CHECK(e0 - e > 1e-3 * std::abs(e0));  // a real decrease, not rounding
}

TEST_CASE("more host VBD iterations bring the substep closer to the Newton minimum", "[vbd]") {
  const SimLayout start = test::moving_cloth(12, 1e4, 1e-3, kH);
  VbdReference probe(start, kH, 0);
  probe.substep();
  const std::vector<Float4> predicted = probe.predicted();
  const auto newton = newton::newton_reference(start, predicted, kH);
  REQUIRE(newton.status == newton::NewtonStatus::converged);
  SimLayout at_prediction = start;
  at_prediction.x = predicted;
  const double e0 = energy::incremental_potential(at_prediction, predicted, kH);
  double previous = 1.0;
  for (int iterations : {1, 2, 4, 8, 16, 32}) {
    VbdReference ref(start, kH, iterations);
    ref.substep();
    const double e = energy::incremental_potential(ref.state(), predicted, kH);
    const double relative = (e - newton.energy) / (e0 - newton.energy);
    INFO("iterations " << iterations << " relative energy error " << relative);
    CHECK(e >= newton.energy - 1e-9 * std::abs(newton.energy));  // not below the minimum
    CHECK(relative < previous);
    previous = relative;
  }
}

TEST_CASE("pinned particles never move in the host VBD", "[vbd]") {
  const auto m = model::build_model(scene::parse_scene(test::hanging_cloth_yaml(8), "s.yaml", "."));
  VbdReference ref(make_sim_layout(m), kH, 8);
  for (int s = 0; s < 20; ++s) ref.substep();
  int pinned = 0;
  for (std::size_t i = 0; i < m.particles.size(); ++i) {
    if (m.particles.inv_mass[i] != 0.0) continue;
    ++pinned;
    CHECK(ref.state().x[i].x == float(m.particles.position[i].x()));
    CHECK(ref.state().x[i].y == float(m.particles.position[i].y()));
    CHECK(ref.state().x[i].z == float(m.particles.position[i].z()));
  }
  CHECK(pinned == 2);
}

TEST_CASE("the host VBD keeps every particle on or above the ground", "[vbd]") {
  const SimLayout start = moving_cloth_over_ground();
  VbdReference ref(start, kH, 8);
  for (int s = 0; s < 5; ++s) ref.substep();
  int on_ground = 0;
  for (const Float4& p : ref.state().x) {
    CHECK(p.y >= start.ground_y);
    on_ground += p.y == start.ground_y;
  }
  CHECK(on_ground > 0);  // the ground did work
}

TEST_CASE("the host VBD on 2 threads gives the 1-thread result bit for bit", "[vbd]") {
  // Vertices of one color share no element, so their order does not matter.
  const SimLayout start = moving_cloth_over_ground();
  check_same_substeps(VbdReference(start, kH, 8, 1), VbdReference(start, kH, 8, 2), start);
}

TEST_CASE("the host VBD's lanes give the one-vertex-at-a-time result bit for bit", "[vbd]") {
  // Lanes gather springs and isometric stencils as 8-float vectors, dihedral
  // stencils lane by lane; the damped springs' terms follow per vertex.
  const std::string variant = GENERATE("isometric", "half dihedral, damped springs");
  INFO(variant);
  SimLayout start = moving_cloth_over_ground();
  if (variant != "isometric") {
    for (std::size_t k = 0; k < start.bend.size(); k += 2) start.bend[k].model = ATS_BEND_DIHEDRAL;
    for (std::size_t k = 0; k < start.stretch.size(); k += 3) start.stretch[k].damping = 0.05f;
  }
  for (const int threads : {1, 2}) {
    check_same_substeps(VbdReference(start, kH, 8, threads), VbdReference(start, kH, 8, threads, true), start);
  }
}

TEST_CASE("the host VBD refuses fewer than 1 thread and infinitely stiff constraints", "[vbd]") {
  const SimLayout start = test::moving_cloth(4, 1e4, 1e-3, kH, 0);
  CHECK_THROWS_AS(VbdReference(start, kH, 8, 0), Error);
  SimLayout hard = start;
  hard.stretch.front().compliance = 0.0f;
  CHECK_THROWS_AS(VbdReference(hard, kH, 8), Error);
}
