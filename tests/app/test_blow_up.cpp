// Blow-up detection relative to the scene (app/blow_up.hpp), against
// displacements worked out by hand.
#include <catch2/catch.hpp>

#include <cmath>
#include <limits>
#include <vector>

#include "app/blow_up.hpp"

using namespace atssim::app;

namespace {

// Two particles 3 m apart along x, at height y.
std::vector<float> pair_at(float y) { return {0.0f, y, 0.0f, 3.0f, y, 0.0f}; }

}  // namespace

TEST_CASE("the bounds come from the initial bounding box, speeds, gravity and the substep", "[fast]") {
  const std::vector<float> v = {0.0f, 0.0f, 4.0f, 0.0f, 0.0f, 0.0f};
  const BlowUpBounds b = blow_up_bounds(pair_at(1.0f), v, 9.81, 1.0 / 60.0, 4);
  CHECK(b.scene_size == Approx(3.0));
  CHECK(b.speed0 == Approx(4.0));
  CHECK(b.substep_dt == Approx(1.0 / 240.0));
  // 4 substeps × 10 × (3 m + (4 m/s + 9.81 m/s² · 1 s) · 1/240 s)
  CHECK(max_frame_displacement(b, 1.0) == Approx(4 * 10 * (3.0 + 13.81 / 240.0)));
}

TEST_CASE("a scene far from the origin is not a blow-up, a jump of many scene sizes is", "[fast]") {
  const BlowUpBounds b = blow_up_bounds(pair_at(2.0e6f), {}, 9.81, 1.0 / 60.0, 4);
  CHECK_FALSE(find_blow_up(pair_at(2.0e6f), pair_at(2.0e6f - 1.0f), b, 1.0 / 60.0, 1));
  // 8.7e5 m in one frame from a 3 m scene: far beyond 4 × 10 × 3 m.
  const auto why =
      find_blow_up(pair_at(1.0f), pair_at(8.7e5f), blow_up_bounds(pair_at(1.0f), {}, 9.81, 1 / 60.0, 4), 1.0 / 60.0, 1);
  REQUIRE(why);
  CHECK(why->find("particle 0 moved") != std::string::npos);
}

TEST_CASE("free fall under strong gravity and long frames is within the bounds", "[fast]") {
  // 10 s frames, one substep, g = 1e5: the first frame falls g·t²/2 = 5e6 m.
  const BlowUpBounds b = blow_up_bounds(pair_at(0.0f), {}, 1e5, 10.0, 1);
  CHECK_FALSE(find_blow_up(pair_at(0.0f), pair_at(-5.0e6f), b, 10.0, 1));
}

TEST_CASE("a non-finite position is a blow-up, naming the particle", "[fast]") {
  const BlowUpBounds b = blow_up_bounds(pair_at(1.0f), {}, 9.81, 1.0 / 60.0, 4);
  std::vector<float> after = pair_at(1.0f);
  after[4] = std::numeric_limits<float>::quiet_NaN();
  const auto why = find_blow_up(pair_at(1.0f), after, b, 1.0 / 60.0, 1);
  REQUIRE(why);
  CHECK(why->find("particle 1") != std::string::npos);
  CHECK(why->find("non-finite") != std::string::npos);
}
