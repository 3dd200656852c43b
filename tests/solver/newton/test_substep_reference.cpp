#include <catch2/catch.hpp>

#include <cmath>

#include "solver/newton/substep_reference.hpp"

using namespace atssim;
using namespace atssim::solver;

namespace {

// A free particle on a spring to a pinned one, moving and falling.
SimLayout particle_on_spring() {
  SimLayout layout;
  layout.x = {{0, 0, 0, 0}, {0.3f, -0.4f, 0.1f, 100.0f}};
  layout.v = {{}, {0.5f, 0.2f, -0.1f, 0.0f}};
  layout.stretch = {{0, 1, 0.25f, 1e-3f, 0.0f}};
  layout.gravity = {0.0f, -9.81f, 0.0f, 0.0f};
  return layout;
}

}  // namespace

TEST_CASE("the relative error is 0 at the Newton minimum and 1 at the predicted positions", "[newton]") {
  const SimLayout s = particle_on_spring();
  const double h = 0.01;
  const auto r = newton::substep_reference(s, h);
  REQUIRE(r.newton.status == newton::NewtonStatus::converged);
  REQUIRE(r.span() > 0.0);
  CHECK(r.relative_error(s, r.predicted) == Approx(1.0).epsilon(1e-12));  // no ground: x~ is E0's point
  // x* in float32 sits within the float32 floor of 0.
  const SimLayout exact = newton::exact_step(s, r);
  const double at_minimum = r.relative_error(s, exact.x);
  CHECK(at_minimum >= -r.y_floor);
  CHECK(at_minimum <= r.y_floor + 1e-12);
  CHECK(r.y_floor >= 0.0);
  CHECK(r.y_floor < 1e-6);
}

TEST_CASE("the exact step moves to x* with the velocity (x* - x) / h, and keeps the pinned particle", "[newton]") {
  const SimLayout s = particle_on_spring();
  const double h = 0.01;
  const auto r = newton::substep_reference(s, h);
  const SimLayout next = newton::exact_step(s, r);
  CHECK(next.x[1].x == Approx(r.newton.x[3]).epsilon(1e-6));
  CHECK(next.x[1].y == Approx(r.newton.x[4]).epsilon(1e-6));
  CHECK(next.v[1].y == Approx((r.newton.x[4] - double(s.x[1].y)) / h).epsilon(1e-4));
  CHECK(next.x[1].w == s.x[1].w);
  CHECK(next.x[0].x == 0.0f);
  CHECK(next.v[0].x == 0.0f);
}

TEST_CASE("a state with nothing to solve has no span, y 0 and no float32 floor", "[newton]") {
  SimLayout s;  // one free particle at rest, no gravity, no elements: x~ = x = x*
  s.x = {{0.1f, 0.2f, 0.3f, 1.0f}};
  s.v = {{}};
  const auto r = newton::substep_reference(s, 0.01);
  CHECK(r.span() <= 0.0);
  CHECK(r.relative_error(s, s.x) == 0.0);
  CHECK(std::isnan(r.y_floor));
}
