#include <catch2/catch.hpp>

#include <cstring>

#include "model/cloth_builder.hpp"
#include "scene/scene_loader.hpp"
#include "solver/energy/moving_cloth.hpp"
#include "solver/xpbd/xpbd_reference.hpp"
#include "util/error.hpp"

using namespace atssim;
using namespace atssim::solver;
using namespace atssim::solver::xpbd;

namespace {

constexpr double kH = 1.0 / 240.0;

bool same_bits(const std::vector<Float4>& a, const std::vector<Float4>& b) {
  return a.size() == b.size() && std::memcmp(a.data(), b.data(), a.size() * sizeof(Float4)) == 0;
}

void check_threads_agree(const SimLayout& start) {
  XpbdReference one(start, {kH, 8}, 1);
  XpbdReference two(start, {kH, 8}, 2);
  for (int s = 0; s < 5; ++s) {
    one.substep();
    two.substep();
  }
  CHECK(same_bits(one.state().x, two.state().x));
  CHECK(same_bits(one.state().v, two.state().v));
  CHECK(one.residual_rms() == two.residual_rms());  // the lambdas too
  CHECK_FALSE(same_bits(one.state().x, start.x));   // it moved
}

}  // namespace

TEST_CASE("the host XPBD on 2 threads gives the 1-thread result bit for bit on a cloth over the ground") {
  // Constraints of one color block share no movable particle, so their order
  // does not matter.
  SimLayout start = test::moving_cloth(16, 1e4, 1e-3, kH);
  float lowest = start.x.front().y;
  for (const Float4& p : start.x) lowest = std::min(lowest, p.y);
  start.has_ground = true;
  start.ground_y = lowest + 2e-3f;
  check_threads_agree(start);
}

TEST_CASE("the host XPBD on 2 threads gives the 1-thread result bit for bit on a StVK solid") {
  const std::string yaml =
      "objects:\n"
      "  - type: solid\n"
      "    box: {size: [0.1, 0.4, 0.1], resolution: [2, 8, 2]}\n"
      "    material: {density: 1000, youngs_modulus: 1.0e6, poisson_ratio: 0.3, model: stvk}\n"
      "    pins: {boxes: [{min: [-1, 0.19, -1], max: [1, 0.21, 1]}]}\n";
  const SimLayout start = make_sim_layout(model::build_model(scene::parse_scene(yaml, "s.yaml", ".")));
  REQUIRE(start.tet_blocks.size() > 2);
  check_threads_agree(start);
}

TEST_CASE("the host XPBD refuses fewer than 1 thread") {
  const SimLayout start = test::moving_cloth(4, 1e4, 1e-3, kH, 0);
  CHECK_THROWS_AS(XpbdReference(start, {kH, 8}, 0), Error);
}
