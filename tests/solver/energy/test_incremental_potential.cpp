#include <catch2/catch.hpp>

#include <Eigen/Dense>

#include "solver/energy/energy_plan.hpp"
#include "solver/energy/finite_differences.hpp"
#include "solver/energy/incremental_potential.hpp"
#include "solver/energy/moving_cloth.hpp"
#include "solver/energy/potential_evaluation.hpp"
#include "solver/energy/predicted_positions.hpp"
#include "util/error.hpp"

using namespace atssim;
using namespace atssim::solver;
using namespace atssim::solver::energy;

namespace {

constexpr double kH = 1.0 / 240.0;

// E straight from its definition (He et al. 2025 Eq. 1), plain Eigen.
double energy_by_definition(const SimLayout& layout, const std::vector<Float4>& predicted, double h) {
  auto p = [](const Float4& f) { return Eigen::Vector3d(f.x, f.y, f.z); };
  double e = 0.0;
  for (std::size_t i = 0; i < layout.x.size(); ++i) {
    if (layout.x[i].w > 0.0f)
      e += 0.5 / (h * h) / double(layout.x[i].w) * (p(layout.x[i]) - p(predicted[i])).squaredNorm();
  }
  for (const auto& c : layout.stretch) {
    const double d = (p(layout.x[c.a]) - p(layout.x[c.b])).norm() - double(c.rest);
    e += 0.5 / double(c.compliance) * d * d;
  }
  for (const auto& c : layout.bend) {
    Eigen::Vector3d sum = Eigen::Vector3d::Zero();
    for (int i = 0; i < 4; ++i) sum += double(c.K[i]) * p(layout.x[c.v[i]]);
    e += 0.5 / double(c.compliance) * double(c.scale) * sum.squaredNorm();
  }
  return e;
}

}  // namespace

TEST_CASE("predicted positions equal the XPBD predict step bit for bit", "[energy]") {
  const SimLayout start = test::moving_cloth(8, 1e3, 1e-3, kH);
  xpbd::XpbdReference predict_only(start, {kH, 0});  // no iterations: predict, then update velocity
  predict_only.substep();
  const auto predicted = predicted_positions(start, kH);
  REQUIRE(predicted.size() == start.x.size());
  int moved = 0;
  for (std::size_t i = 0; i < predicted.size(); ++i) {
    const auto& a = predicted[i];
    const auto& b = predict_only.state().x[i];
    CHECK((a.x == b.x && a.y == b.y && a.z == b.z && a.w == b.w));
    moved += a.y != start.x[i].y;
  }
  CHECK(moved > 50);
}

TEST_CASE("the incremental potential of a layout equals its definition", "[energy]") {
  const SimLayout start = test::moving_cloth(8, 1e3, 1e-3, kH);
  const auto predicted = predicted_positions(start, kH);
  xpbd::XpbdReference ref(start, {kH, 4});
  ref.substep();
  const double e = incremental_potential(ref.state(), predicted, kH);
  CHECK(e == Approx(energy_by_definition(ref.state(), predicted, kH)).epsilon(1e-12));
  // All three terms are present on this state.
  const auto terms = energy_terms(make_incremental_potential(ref.state(), predicted, kH), positions_of(ref.state().x));
  INFO("inertia " << terms.inertia << " stretch " << terms.stretch << " bend " << terms.bend);
  CHECK(terms.inertia > 0.0);
  CHECK(terms.stretch > 0.0);
  CHECK(terms.bend > 0.0);
}

TEST_CASE("the assembled gradient and Hessian match finite differences on a moving cloth", "[energy]") {
  const SimLayout start = test::moving_cloth(5, 1e3, 1e-3, kH);
  const auto predicted = predicted_positions(start, kH);
  const IncrementalPotential p = make_incremental_potential(start, predicted, kH);
  const Eigen::VectorXd x = positions_of(start.x);
  const Eigen::VectorXd g = gradient(p, x);
  Eigen::VectorXd fd = test::fd_gradient([&](const Eigen::VectorXd& y) { return total_energy(p, y); }, x);
  for (int i = 0; i < p.particle_count(); ++i) {
    if (p.is_free(i)) continue;
    CHECK(g.segment<3>(3 * i).norm() == 0.0);  // pinned: no variables
    fd.segment<3>(3 * i).setZero();
  }
  INFO("|g| " << g.norm() << " |g - fd| " << (g - fd).norm());
  CHECK((g - fd).norm() <= 1e-4 * g.norm());

  const auto triplets = hessian_triplets(p, x, false);
  Eigen::SparseMatrix<double> H(x.size(), x.size());
  H.setFromTriplets(triplets.begin(), triplets.end());
  const Eigen::MatrixXd dense(H);
  Eigen::MatrixXd jac = test::fd_jacobian([&](const Eigen::VectorXd& y) { return gradient(p, y); }, x);
  for (int i = 0; i < p.particle_count(); ++i) {
    if (!p.is_free(i)) jac.middleCols<3>(3 * i).setZero();  // pinned columns are left out too
  }
  INFO("|H| " << dense.norm() << " |H - fd| " << (dense - jac).norm());
  CHECK((dense - jac).norm() <= 1e-4 * dense.norm());
  CHECK((dense - dense.transpose()).norm() <= 1e-12 * dense.norm());
}

TEST_CASE("the projected Hessian plus M/h^2 is positive definite", "[energy]") {
  // Compress the cloth so many springs are shorter than their rest length.
  SimLayout state = test::moving_cloth(5, 1e3, 1e-3, kH);
  const auto predicted = predicted_positions(state, kH);
  for (auto& q : state.x) {
    q.x *= 0.8f;
    q.z *= 0.8f;
  }
  const IncrementalPotential p = make_incremental_potential(state, predicted, kH);
  const Eigen::VectorXd x = positions_of(state.x);
  for (bool project : {false, true}) {
    const auto triplets = hessian_triplets(p, x, project);
    Eigen::SparseMatrix<double> H(x.size(), x.size());
    H.setFromTriplets(triplets.begin(), triplets.end());
    // Without the inertia term: the elastic part alone.
    Eigen::MatrixXd elastic(H);
    for (int i = 0; i < p.particle_count(); ++i) {
      if (p.is_free(i)) elastic.block<3, 3>(3 * i, 3 * i) -= p.mass[i] / (kH * kH) * Eigen::Matrix3d::Identity();
    }
    const double lowest = Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd>(elastic).eigenvalues().minCoeff();
    INFO((project ? "projected" : "exact") << " lowest eigenvalue of the elastic Hessian " << lowest);
    if (project) {
      CHECK(lowest >= -1e-9 * elastic.norm());
    } else {
      CHECK(lowest < -1e-3 * elastic.norm());  // compressed springs: indefinite
    }
  }
}

TEST_CASE("a constraint with compliance 0 has no incremental potential", "[energy]") {
  SimLayout state = test::moving_cloth(4, 1e3, 1e-3, kH);
  const auto predicted = predicted_positions(state, kH);
  SECTION("stretch") { state.stretch[3].compliance = 0.0f; }
  SECTION("bend") { state.bend[1].compliance = 0.0f; }
  CHECK_THROWS_AS(make_incremental_potential(state, predicted, kH), atssim::Error);
  CHECK_THROWS_WITH(incremental_potential(state, predicted, kH), Catch::Contains("finite stiffness"));
  CHECK_THROWS_AS(make_energy_plan(state, predicted, kH), atssim::Error);
}

TEST_CASE("the energy plan is one task of program xpbd_energy covering every particle and constraint", "[energy]") {
  const SimLayout state = test::moving_cloth(4, 1e3, 1e-3, kH);
  EnergyBuffers ids;
  const plan::SubstepPlan plan = make_energy_plan(state, predicted_positions(state, kH), kH, &ids);
  CHECK(plan.program == "xpbd_energy");
  REQUIRE(plan.graph.size() == 1);
  REQUIRE(plan.launches.size() == 1);
  const EnergyOutput where = energy_output(state);
  CHECK(where.size == int(state.x.size() + state.stretch.size() + state.bend.size()));
  CHECK(plan.buffers[ids.energy].initial.size() == where.size * sizeof(float));
  int covered = 0;
  for (const auto& l : plan.launches[0]) {
    CHECK(l.range.first == 0);
    covered += l.range.count;
  }
  CHECK(covered == where.size);
}
