// Dihedral-angle bending (kernels/common/energy_dihedral.h) in double. The
// Hessian is the Gauss-Newton one: checked for symmetry and PSD, and against
// finite differences only where it is exact (theta = theta_0).
#include "solver/energy/element_math.hpp"  // first: the double instance of the shared math

#include <catch2/catch.hpp>

#include <cmath>
#include <random>

#include <Eigen/Eigenvalues>

#include "solver/energy/element_checks.hpp"
#include "solver/energy/finite_differences.hpp"

using namespace atssim;
using namespace atssim::solver::energy::f64;
using test::ElementFunctions;

namespace {

ElementFunctions dihedral(double rest_angle, double k) {
  ElementFunctions f;
  f.vertices = 4;
  f.energy = [=](const ats_vec3* x) { return ats_dihedral_energy(x, rest_angle, k); };
  f.gradient = [=](const ats_vec3* x, int a) { return ats_dihedral_gradient(x, rest_angle, k, a); };
  f.hessian = [=](const ats_vec3* x, int a, int b) { return ats_dihedral_hessian_gn(x, k, a, b); };
  return f;
}

double angle_of(const Eigen::VectorXd& q) {
  ats_vec3 x[4];
  ElementFunctions::unpack(q, x, 4);
  return ats_dihedral_angle(x);
}

// Edge along x, wings on either side, folded by up to ~110 degrees, randomly placed.
std::vector<Eigen::Vector3d> random_stencil(std::mt19937& rng) {
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  const double fold_a = 1.0 * u(rng), fold_b = 1.0 * u(rng);
  std::vector<Eigen::Vector3d> x = {{0, 0, 0},
                                    {1 + 0.2 * u(rng), 0, 0},
                                    {0.5 + 0.4 * u(rng), std::cos(fold_a), std::sin(fold_a)},
                                    {0.5 + 0.4 * u(rng), -std::cos(fold_b), std::sin(fold_b)}};
  const Eigen::Matrix3d R = test::random_rotation(rng);
  const Eigen::Vector3d t(u(rng), u(rng), u(rng));
  for (auto& p : x) p = R * p + t;
  return x;
}

}  // namespace

TEST_CASE("the dihedral angle is 0 flat and +-pi/2 for wings folded to a right angle", "[energy][dihedral]") {
  const auto angle = [](std::vector<Eigen::Vector3d> x) { return angle_of(test::pack(x)); };
  CHECK(angle({{0, 0, 0}, {1, 0, 0}, {0.5, 1, 0}, {0.5, -1, 0}}) == Approx(0.0).margin(1e-15));
  // Wing 2 lifted along its normal n_a = +z: positive.
  CHECK(angle({{0, 0, 0}, {1, 0, 0}, {0.5, 0, 1}, {0.5, -1, 0}}) == Approx(M_PI / 2).epsilon(1e-14));
  CHECK(angle({{0, 0, 0}, {1, 0, 0}, {0.5, 0, -1}, {0.5, -1, 0}}) == Approx(-M_PI / 2).epsilon(1e-14));
}

TEST_CASE("dihedral gradient matches central finite differences", "[energy][dihedral]") {
  std::mt19937 rng(31);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  for (int n = 0; n < 50; ++n) {
    const Eigen::VectorXd q = test::pack(random_stencil(rng));
    const ElementFunctions f = dihedral(0.5 * u(rng), 1.0 + 0.5 * u(rng));
    const Eigen::VectorXd g = f.gradient_at(q);
    const Eigen::VectorXd fd = test::fd_gradient([&](const Eigen::VectorXd& y) { return f.energy_at(y); }, q);
    INFO("stencil " << n << " theta " << angle_of(q) << " |g| " << g.norm() << " |g - fd| " << (g - fd).norm());
    CHECK((g - fd).norm() <= 1e-4 * g.norm());
  }
}

TEST_CASE("the Gauss-Newton dihedral Hessian is symmetric and PSD", "[energy][dihedral]") {
  std::mt19937 rng(32);
  for (int n = 0; n < 50; ++n) {
    const Eigen::VectorXd q = test::pack(random_stencil(rng));
    const Eigen::MatrixXd H = dihedral(0.3, 2.0).hessian_at(q);
    CHECK((H - H.transpose()).norm() <= 1e-12 * H.norm());
    Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> eig(H);
    CHECK(eig.eigenvalues().minCoeff() >= -1e-12 * H.norm());
  }
}

TEST_CASE("at the rest angle the Gauss-Newton Hessian equals finite differences of the gradient",
          "[energy][dihedral]") {
  // There 2 k (theta - theta_0) d2theta vanishes, so this checks dtheta/dx
  // as a derivative, not only the energy's gradient.
  std::mt19937 rng(33);
  for (int n = 0; n < 50; ++n) {
    const Eigen::VectorXd q = test::pack(random_stencil(rng));
    const ElementFunctions f = dihedral(angle_of(q), 1.5);
    const Eigen::MatrixXd H = f.hessian_at(q);
    const Eigen::MatrixXd fd = test::fd_jacobian([&](const Eigen::VectorXd& y) { return f.gradient_at(y); }, q);
    INFO("stencil " << n << " |H| " << H.norm() << " |H - fd| " << (H - fd).norm());
    CHECK((H - fd).norm() <= 1e-4 * H.norm());
  }
}

TEST_CASE("a dihedral stencil at its rest angle, moved rigidly, has zero energy and zero force", "[energy][dihedral]") {
  std::mt19937 rng(34);
  for (int n = 0; n < 20; ++n) {
    const auto rest = random_stencil(rng);
    const auto xr = test::to_ats(rest);
    const double k = ats_dihedral_rest_stiffness(xr.data(), 1e-2);
    const ElementFunctions f = dihedral(ats_dihedral_angle(xr.data()), k);
    const Eigen::Matrix3d R = test::random_rotation(rng);
    for (bool moved : {false, true}) {
      std::vector<Eigen::Vector3d> x = rest;
      if (moved) {
        for (auto& p : x) p = R * p + Eigen::Vector3d(0.3, -2.0, 1.5);
      }
      const Eigen::VectorXd q = test::pack(x);
      CHECK(f.energy_at(q) <= 1e-24 * k);
      CHECK(f.gradient_at(q).norm() <= 1e-12 * k);
      CHECK(f.energy_at(q) == Approx(0.0).margin(1e-30));
    }
  }
}

TEST_CASE("dihedral energy is unchanged by a rotation of the deformed shape", "[energy][dihedral]") {
  std::mt19937 rng(35);
  for (int n = 0; n < 20; ++n) {
    const auto x = random_stencil(rng);
    const ElementFunctions f = dihedral(0.2, 1.0);
    const Eigen::Matrix3d R = test::random_rotation(rng);
    std::vector<Eigen::Vector3d> rx;
    for (const auto& p : x) rx.push_back(R * p);
    CHECK(f.energy_at(test::pack(rx)) == Approx(f.energy_at(test::pack(x))).epsilon(1e-12));
  }
}

TEST_CASE("a degenerate dihedral stencil gives finite zero forces", "[energy][dihedral]") {
  const ElementFunctions f = dihedral(0.3, 1.0);
  // Wing 2 on the edge line (zero area), then a zero-length edge.
  for (const auto& x : {std::vector<Eigen::Vector3d>{{0, 0, 0}, {1, 0, 0}, {0.5, 0, 0}, {0.5, -1, 0}},
                        std::vector<Eigen::Vector3d>{{0, 0, 0}, {0, 0, 0}, {0.5, 1, 0}, {0.5, -1, 0}}}) {
    const Eigen::VectorXd q = test::pack(x);
    CHECK(std::isfinite(f.energy_at(q)));
    CHECK(f.gradient_at(q).norm() == 0.0);
    CHECK(f.hessian_at(q).norm() == 0.0);
  }
}

TEST_CASE("the rest stiffness is k |e|^2 / (A_a + A_b)", "[energy][dihedral]") {
  const std::vector<Eigen::Vector3d> x = {{0, 0, 0}, {2, 0, 0}, {1, 1, 0}, {1, -3, 0}};  // areas 1 and 3
  const auto xa = test::to_ats(x);
  CHECK(ats_dihedral_rest_stiffness(xa.data(), 0.5) == Approx(0.5 * 4.0 / 4.0).epsilon(1e-15));
}
