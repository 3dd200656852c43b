#include <catch2/catch.hpp>

#include <cmath>
#include <sstream>

#include "solver/energy/incremental_potential.hpp"
#include "solver/energy/moving_cloth.hpp"
#include "solver/energy/potential_evaluation.hpp"
#include "solver/energy/predicted_positions.hpp"
#include "solver/newton/newton_reference.hpp"
#include "util/error.hpp"

using namespace atssim;
using namespace atssim::solver;

namespace {

constexpr double kH = 1.0 / 240.0;

}  // namespace

TEST_CASE("Newton finds the closed-form minimum of a particle on a spring", "[newton]") {
  // A free particle of mass m on a spring to a pinned one at the origin: the
  // minimum lies on the ray to x~ at radius r with m/h^2 (r - r~) + k (r - L) = 0.
  SimLayout layout;
  const float w = 100.0f;  // inverse mass
  layout.x = {{0, 0, 0, 0}, {0.3f, -0.4f, 0.1f, w}};
  layout.v = {{}, {}};
  layout.stretch = {{0, 1, 0.25f, 1e-3f, 0.0f}};
  const std::vector<Float4> predicted = layout.x;
  const double h = 0.01;
  const auto r = newton::newton_reference(layout, predicted, h);
  REQUIRE(r.status == newton::NewtonStatus::converged);
  const Eigen::Vector3d tilde(0.3f, -0.4f, 0.1f);
  const double m_h2 = 1.0 / double(w) / (h * h), k = 1.0 / double(1e-3f), L = double(0.25f);
  const double radius = (m_h2 * tilde.norm() + k * L) / (m_h2 + k);
  const Eigen::Vector3d expected = radius * tilde.normalized();
  INFO("iterations " << r.iterations << " relative gradient " << r.relative_gradient);
  CHECK((r.x.segment<3>(3) - expected).norm() <= 1e-12);
  CHECK(r.x.segment<3>(0).norm() == 0.0);  // pinned stays
}

TEST_CASE("with a ground plane Newton finds the bound-constrained minimum of a particle on a spring", "[newton]") {
  // As above, with x~ below the ground y = -0.2: the minimum sits on the
  // ground, and in the xz plane on the ray to x~'s footprint at distance s with
  // m/h^2 (s - s~) + k (r - L) s / r = 0, r = |(s, 0.2)| (found by bisection).
  SimLayout layout;
  const float w = 100.0f;
  layout.x = {{0, 0, 0, 0}, {0.3f, -0.4f, 0.1f, w}};
  layout.v = {{}, {}};
  layout.stretch = {{0, 1, 0.25f, 1e-3f, 0.0f}};
  layout.has_ground = true;
  layout.ground_y = -0.2f;
  const double h = 0.01;
  const auto r = newton::newton_reference(layout, layout.x, h);
  REQUIRE(r.status == newton::NewtonStatus::converged);
  const double m_h2 = 1.0 / double(w) / (h * h), k = 1.0 / double(1e-3f), L = double(0.25f);
  const Eigen::Vector2d foot(0.3f, 0.1f);
  const double height = -double(-0.2f), s_tilde = foot.norm();
  const auto force = [&](double s) {
    const double radius = std::hypot(s, height);
    return m_h2 * (s - s_tilde) + k * (radius - L) * s / radius;
  };
  double lo = 0.0, hi = s_tilde;  // force(0) < 0 < force(s~)
  for (int i = 0; i < 200; ++i) (force(0.5 * (lo + hi)) < 0 ? lo : hi) = 0.5 * (lo + hi);
  const Eigen::Vector2d xz = 0.5 * (lo + hi) * foot.normalized();
  CHECK(r.x[4] == double(-0.2f));  // on the ground, not below it
  CHECK(std::abs(r.x[3] - xz.x()) <= 1e-12);
  CHECK(std::abs(r.x[5] - xz.y()) <= 1e-12);
  // KKT: the ground holds the particle up (E would fall by moving it down).
  const energy::IncrementalPotential problem = energy::make_incremental_potential(layout, layout.x, h);
  CHECK(energy::gradient(problem, r.x)[4] > 0.0);
}

TEST_CASE("Newton converges on a moving cloth and bounds XPBD's energy from below", "[newton]") {
  const SimLayout start = test::moving_cloth(10, 1e3, 1e-3, kH);
  const auto predicted = energy::predicted_positions(start, kH);
  const energy::IncrementalPotential problem = energy::make_incremental_potential(start, predicted, kH);

  const newton::NewtonResult star = newton::newton_reference(start, predicted, kH);
  INFO("Newton: " << newton::to_string(star.status) << " after " << star.iterations << " iterations, relative |grad| "
                  << star.relative_gradient << ", |grad| " << star.gradient_norm << ", E* " << star.energy);
  REQUIRE(star.status == newton::NewtonStatus::converged);
  CHECK(star.relative_gradient < 1e-8);
  CHECK(star.iterations < 30);

  // XPBD starts at x~ (k = 0) and should approach E* as iterations rise.
  const double e0 = energy::total_energy(problem, problem.predicted);
  REQUIRE(e0 > star.energy);
  std::vector<double> y;
  std::ostringstream table;
  for (int k : {1, 2, 4, 8, 16, 32, 64}) {
    xpbd::XpbdReference xpbd_run(start, {kH, k});
    xpbd_run.substep();
    const double ek = energy::incremental_potential(xpbd_run.state(), predicted, kH);
    y.push_back((ek - star.energy) / (e0 - star.energy));
    table << " k=" << k << ": E_k " << ek << " y_k " << y.back() << ";";
    INFO("k " << k << " E_k " << ek << " y_k " << y.back());
    CHECK(star.energy <= ek + 1e-12 * std::abs(star.energy));
  }
  INFO("E_0 " << e0 << table.str());
  for (std::size_t i = 1; i < y.size(); ++i) CHECK(y[i] < y[i - 1]);
}

TEST_CASE("Newton refuses an infinitely stiff constraint", "[newton]") {
  SimLayout start = test::moving_cloth(4, 1e3, 1e-3, kH);
  start.stretch[0].compliance = 0.0f;
  const auto predicted = energy::predicted_positions(start, kH);
  CHECK_THROWS_WITH(newton::newton_reference(start, predicted, kH), Catch::Contains("finite stiffness"));
}
