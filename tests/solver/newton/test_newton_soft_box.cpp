// The Newton reference on soft bodies: one implicit-Euler substep of a small
// hanging box of stable neo-Hookean or StVK tets.
#include <catch2/catch.hpp>

#include <algorithm>
#include <string>

#include "solver/energy/incremental_potential.hpp"
#include "solver/energy/moving_soft_box.hpp"
#include "solver/energy/potential_evaluation.hpp"
#include "solver/energy/predicted_positions.hpp"
#include "solver/newton/newton_reference.hpp"

using namespace atssim;
using namespace atssim::solver;

namespace {

constexpr double kH = 1.0 / 240.0;

}  // namespace

TEST_CASE("Newton converges on one substep of a moving soft box and lowers E below E(x~)", "[newton][tet]") {
  // 2 x 2 x 2 cells, nu = 0.3, density 1000, top face pinned. E = 1e4 Pa at
  // h = 1/240 is dominated by inertia; E = 1e6 Pa at h = 1/30, strongly
  // deformed, by elasticity (the line search and the projection matter).
  const std::string model = GENERATE("neo_hookean", "stvk");
  const auto [youngs, h, strain] = GENERATE(table<double, double, double>({{1e4, kH, 0.1}, {1e6, 1.0 / 30.0, 0.3}}));
  const SimLayout start = test::moving_soft_box(2, model, 1, strain, youngs);
  const auto predicted = energy::predicted_positions(start, h);
  const energy::IncrementalPotential problem = energy::make_incremental_potential(start, predicted, h);
  REQUIRE(problem.tets.size() == 48);

  const newton::NewtonResult star = newton::newton_reference(start, predicted, h);
  const double e_tilde = energy::total_energy(problem, problem.predicted);
  const energy::EnergyTerms terms = energy::energy_terms(problem, star.x);
  INFO(model << ", E " << youngs << " Pa, h " << h << ": " << newton::to_string(star.status) << " after "
             << star.iterations << " iterations, relative |grad| " << star.relative_gradient << ", |grad| "
             << star.gradient_norm << ", E(x~) " << e_tilde << ", E* " << star.energy << " (inertia " << terms.inertia
             << ", tet " << terms.tet << ")");
  REQUIRE(star.status == newton::NewtonStatus::converged);
  CHECK(star.relative_gradient < 1e-8);
  CHECK(star.iterations < 30);
  CHECK(star.energy <= e_tilde);
  CHECK(star.energy < e_tilde);  // x~ is deformed: the elastic forces move it
  CHECK(terms.tet > 0.0);
  // Pinned particles stay where they are.
  for (int i = 0; i < problem.particle_count(); ++i) {
    if (!problem.is_free(i)) CHECK((star.x.segment<3>(3 * i) - problem.predicted.segment<3>(3 * i)).norm() == 0.0);
  }
}

TEST_CASE("Newton with the exact tet Hessian converges near rest as well", "[newton][tet]") {
  // Close to rest the tet Hessians are PSD, so skipping the projection
  // changes nothing but the cost: Newton must still converge.
  const SimLayout start = test::moving_soft_box(2, "neo_hookean", 2, 0.01);
  const auto predicted = energy::predicted_positions(start, kH);
  newton::NewtonSettings settings;
  settings.project_psd = false;
  const newton::NewtonResult star = newton::newton_reference(start, predicted, kH, settings);
  INFO(newton::to_string(star.status) << " after " << star.iterations << " iterations, relative |grad| "
                                      << star.relative_gradient);
  REQUIRE(star.status == newton::NewtonStatus::converged);
  CHECK(star.relative_gradient < 1e-8);
}

TEST_CASE("Newton refuses a tet with a negative Lame lambda", "[newton][tet]") {
  SimLayout start = test::moving_soft_box(1);
  start.tets[0].lambda = -5.0f;
  const auto predicted = energy::predicted_positions(start, kH);
  CHECK_THROWS_WITH(newton::newton_reference(start, predicted, kH), Catch::Contains("lambda >= 0"));
}

TEST_CASE("Newton stops within 20 steps on a body falling freely at rest, at the inertial prediction",
          "[newton][tet]") {
  // Nothing pinned, at rest shape, at rest: x~ = x + h^2 g is a rigid
  // translation, so E = inertia + elasticity is 0 there and nowhere lower:
  // x* = x~ exactly, and |grad E(x0)| at x0 = x~ is rounding, which the
  // relative tolerance cannot go below. Newton must say so in a few steps
  // (NewtonStatus::stalled or converged), not take all max_iterations.
  SimLayout start = test::moving_soft_box(2, "neo_hookean", 1, 0.0);
  float w_free = 0.0f;
  for (const auto& p : start.x) w_free = std::max(w_free, p.w);
  REQUIRE(w_free > 0.0f);
  for (std::size_t i = 0; i < start.x.size(); ++i) {
    if (start.x[i].w == 0.0f) start.x[i].w = w_free;
    start.v[i] = {0.0f, 0.0f, 0.0f, 0.0f};
  }
  const auto predicted = energy::predicted_positions(start, kH);
  const energy::IncrementalPotential problem = energy::make_incremental_potential(start, predicted, kH);
  for (int i = 0; i < problem.particle_count(); ++i) REQUIRE(problem.is_free(i));
  const newton::NewtonResult star = newton::newton_reference(start, predicted, kH);
  INFO(newton::to_string(star.status) << " after " << star.iterations << " iterations, relative |grad| "
                                      << star.relative_gradient);
  CHECK((star.status == newton::NewtonStatus::stalled || star.status == newton::NewtonStatus::converged));
  CHECK(star.iterations <= 20);
  CHECK((star.x - problem.predicted).cwiseAbs().maxCoeff() < 1e-9);
}
