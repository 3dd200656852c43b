// The incremental potential of soft bodies: the tet terms assembled over a
// small box, against finite differences and their definition.
#include <catch2/catch.hpp>

#include <cmath>
#include <limits>
#include <string>

#include <Eigen/Dense>

#include "solver/energy/energy_plan.hpp"
#include "solver/energy/finite_differences.hpp"
#include "solver/energy/incremental_potential.hpp"
#include "solver/energy/moving_soft_box.hpp"
#include "solver/energy/potential_evaluation.hpp"
#include "solver/energy/predicted_positions.hpp"
#include "util/error.hpp"

using namespace atssim;
using namespace atssim::solver;
using namespace atssim::solver::energy;

namespace {

constexpr double kH = 1.0 / 240.0;

Eigen::MatrixXd dense_hessian(const IncrementalPotential& p, const Eigen::VectorXd& x, bool project_psd) {
  const auto triplets = hessian_triplets(p, x, project_psd);
  Eigen::SparseMatrix<double> H(x.size(), x.size());
  H.setFromTriplets(triplets.begin(), triplets.end());
  return Eigen::MatrixXd(H);
}

// The Hessian less M/h^2: the elastic part alone.
Eigen::MatrixXd elastic_hessian(const IncrementalPotential& p, const Eigen::VectorXd& x, bool project_psd) {
  Eigen::MatrixXd H = dense_hessian(p, x, project_psd);
  for (int i = 0; i < p.particle_count(); ++i) {
    if (p.is_free(i)) H.block<3, 3>(3 * i, 3 * i) -= p.mass[i] / (p.h * p.h) * Eigen::Matrix3d::Identity();
  }
  return H;
}

}  // namespace

TEST_CASE("a soft box becomes tet terms of the incremental potential with its top face pinned", "[energy][tet]") {
  const std::string model = GENERATE("neo_hookean", "stvk");
  const SimLayout box = test::moving_soft_box(2, model);
  const IncrementalPotential p = make_incremental_potential(box, predicted_positions(box, kH), kH);
  CHECK(p.tets.size() == 48);  // 2^3 cells, 6 tets each
  CHECK(p.stretch.empty());
  int pinned = 0;
  for (int i = 0; i < p.particle_count(); ++i) pinned += !p.is_free(i);
  CHECK(pinned == 9);  // the 3 x 3 vertices of the top face
  for (const TetTerm& t : p.tets) {
    CHECK(t.model == (model == "stvk" ? TetModel::stvk : TetModel::neo_hookean));
    CHECK(t.mu == Approx(1e4 / 2.6).epsilon(1e-6));
    CHECK(t.lambda == Approx(1e4 * 0.3 / (1.3 * 0.4)).epsilon(1e-6));
  }
}

TEST_CASE("a soft box at rest and at its predicted positions has zero energy and zero gradient", "[energy][tet]") {
  const std::string model = GENERATE("neo_hookean", "stvk");
  const auto m = model::build_model(scene::parse_scene(test::soft_box_yaml(2, 1e4, 0.3, model), "s.yaml", "."));
  const SimLayout rest = make_sim_layout(m);
  const IncrementalPotential p = make_incremental_potential(rest, rest.x, kH);  // x~ = x: no inertia either
  const Eigen::VectorXd x = positions_of(rest.x);
  const EnergyTerms e = energy_terms(p, x);
  INFO("inertia " << e.inertia << " tet " << e.tet << " |g| " << gradient(p, x).norm());
  CHECK(e.inertia == 0.0);
  // What is left is the rounding of the float rest shape (F = I to ~1e-7):
  // far below the scales mu V ~ 4 J and mu L^2 ~ 40 N of a 0.1 m cell.
  const double mu = p.tets[0].mu, cell = 0.1;
  CHECK(std::abs(e.tet) <= 1e-12 * mu * cell * cell * cell);
  CHECK(gradient(p, x).norm() <= 1e-6 * mu * cell * cell);
}

TEST_CASE("a deformed, moving soft box has inertia and tet energy, and E is their sum", "[energy][tet]") {
  const SimLayout box = test::moving_soft_box(2);
  const auto predicted = predicted_positions(box, kH);
  const IncrementalPotential p = make_incremental_potential(box, predicted, kH);
  const EnergyTerms e = energy_terms(p, positions_of(box.x));
  INFO("inertia " << e.inertia << " tet " << e.tet);
  CHECK(e.inertia > 0.0);
  CHECK(e.tet > 0.0);
  CHECK(e.total() == Approx(e.inertia + e.tet).epsilon(1e-15));
  CHECK(incremental_potential(box, predicted, kH) == Approx(e.total()).epsilon(1e-12));
}

TEST_CASE("the soft box gradient matches central finite differences", "[energy][tet]") {
  const std::string model = GENERATE("neo_hookean", "stvk");
  const unsigned seed = GENERATE(1u, 2u, 3u);
  const SimLayout box = test::moving_soft_box(2, model, seed, 0.1);
  const IncrementalPotential p = make_incremental_potential(box, predicted_positions(box, kH), kH);
  const Eigen::VectorXd x = positions_of(box.x);
  const Eigen::VectorXd g = gradient(p, x);
  Eigen::VectorXd fd = test::fd_gradient([&](const Eigen::VectorXd& y) { return total_energy(p, y); }, x);
  for (int i = 0; i < p.particle_count(); ++i) {
    if (p.is_free(i)) continue;
    CHECK(g.segment<3>(3 * i).norm() == 0.0);  // pinned: no variables
    fd.segment<3>(3 * i).setZero();
  }
  INFO(model << " seed " << seed << " |g| " << g.norm() << " |g - fd| " << (g - fd).norm());
  CHECK((g - fd).norm() <= 1e-6 * g.norm());
}

TEST_CASE("the assembled soft box Hessian matches finite differences of the gradient", "[energy][tet]") {
  const std::string model = GENERATE("neo_hookean", "stvk");
  const unsigned seed = GENERATE(1u, 2u, 3u);
  const SimLayout box = test::moving_soft_box(2, model, seed, 0.1);
  const IncrementalPotential p = make_incremental_potential(box, predicted_positions(box, kH), kH);
  const Eigen::VectorXd x = positions_of(box.x);
  const Eigen::MatrixXd H = dense_hessian(p, x, false);
  Eigen::MatrixXd jac = test::fd_jacobian([&](const Eigen::VectorXd& y) { return gradient(p, y); }, x);
  for (int i = 0; i < p.particle_count(); ++i) {
    if (!p.is_free(i)) jac.middleCols<3>(3 * i).setZero();  // pinned columns are left out too
  }
  // Compare the elastic part, which M/h^2 on the diagonal would dwarf.
  const Eigen::MatrixXd elastic = elastic_hessian(p, x, false);
  INFO(model << " seed " << seed << " |H| " << H.norm() << " |H_elastic| " << elastic.norm() << " |H - fd| "
             << (H - jac).norm());
  CHECK((H - jac).norm() <= 1e-6 * elastic.norm());
  CHECK((H - H.transpose()).norm() <= 1e-12 * H.norm());
}

TEST_CASE("the projected soft box Hessian is PSD, the exact one is not under compression", "[energy][tet]") {
  const std::string model = GENERATE("neo_hookean", "stvk");
  SimLayout box = test::moving_soft_box(2, model, 4, 0.1);
  const auto predicted = predicted_positions(box, kH);
  for (auto& q : box.x) {  // squash it to 40 % of its height around its centre
    if (q.w > 0.0f) q.y *= 0.4f;
  }
  const IncrementalPotential p = make_incremental_potential(box, predicted, kH);
  const Eigen::VectorXd x = positions_of(box.x);
  for (bool project : {false, true}) {
    const Eigen::MatrixXd elastic = elastic_hessian(p, x, project);
    const double lowest = Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd>(elastic).eigenvalues().minCoeff();
    INFO(model << (project ? " projected" : " exact") << " lowest eigenvalue of the elastic Hessian " << lowest
               << ", |H| " << elastic.norm());
    if (project) {
      CHECK(lowest >= -1e-10 * elastic.norm());
    } else {
      CHECK(lowest < -1e-3 * elastic.norm());
    }
  }
  // Projection leaves an element that is already PSD alone: at rest nothing changes.
  const auto m = model::build_model(scene::parse_scene(test::soft_box_yaml(2, 1e4, 0.3, model), "s.yaml", "."));
  const SimLayout rest = make_sim_layout(m);
  const IncrementalPotential q = make_incremental_potential(rest, rest.x, kH);
  const Eigen::VectorXd xr = positions_of(rest.x);
  const Eigen::MatrixXd exact = dense_hessian(q, xr, false);
  CHECK((dense_hessian(q, xr, true) - exact).norm() <= 1e-9 * exact.norm());
}

TEST_CASE("a tet without positive shear modulus or with negative lambda is rejected", "[energy][tet]") {
  SimLayout box = test::moving_soft_box(1);
  const auto predicted = predicted_positions(box, kH);
  SECTION("mu = 0") { box.tets[2].mu = 0.0f; }
  SECTION("mu < 0") { box.tets[2].mu = -1.0f; }
  SECTION("lambda < 0") { box.tets[2].lambda = -1.0f; }
  SECTION("lambda NaN") { box.tets[2].lambda = std::numeric_limits<float>::quiet_NaN(); }
  CHECK_THROWS_AS(make_incremental_potential(box, predicted, kH), atssim::Error);
  CHECK_THROWS_WITH(incremental_potential(box, predicted, kH), Catch::Contains("tetrahedron 2 has Lame parameters"));
  CHECK_THROWS_WITH(make_energy_plan(box, predicted, kH), Catch::Contains("mu > 0 and lambda >= 0"));
}

TEST_CASE("a tet of unknown energy model is rejected", "[energy][tet]") {
  SimLayout box = test::moving_soft_box(1);
  box.tets[0].model = 7;
  CHECK_THROWS_WITH(make_incremental_potential(box, predicted_positions(box, kH), kH),
                    Catch::Contains("energy model 7"));
}

TEST_CASE("the energy plan of a soft box has one energy_tet launch covering every tet", "[energy][tet]") {
  const SimLayout box = test::moving_soft_box(2);
  EnergyBuffers ids;
  const plan::SubstepPlan plan = make_energy_plan(box, predicted_positions(box, kH), kH, &ids);
  REQUIRE(ids.tets >= 0);
  CHECK(ids.stretch == -1);
  const EnergyOutput where = energy_output(box);
  CHECK(where.tet_first == int(box.x.size()));
  CHECK(where.size == int(box.x.size() + box.tets.size()));
  REQUIRE(plan.launches.size() == 1);
  int tet_launches = 0;
  for (const auto& l : plan.launches[0]) {
    if (l.function != "energy_tet") continue;
    ++tet_launches;
    CHECK(l.args[3].i32 == where.tet_first);
    CHECK(l.range.count == int(box.tets.size()));
  }
  CHECK(tet_launches == 1);
}
