#include "solver/energy/element_math.hpp"  // first: the double instance of the shared math

#include <catch2/catch.hpp>

#include <random>

#include <Eigen/Eigenvalues>

#include "solver/energy/finite_differences.hpp"

using namespace atssim::solver::energy::f64;

namespace {

// One spring as a function of its 6 coordinates (xa, xb).
struct Spring {
  double rest = 1.0;
  double k = 1.0;

  static ats_vec3 at(const Eigen::VectorXd& q, int i) { return ats_v3(q[3 * i], q[3 * i + 1], q[3 * i + 2]); }
  double energy(const Eigen::VectorXd& q) const { return ats_stretch_energy(at(q, 0), at(q, 1), rest, k); }
  Eigen::VectorXd gradient(const Eigen::VectorXd& q) const {
    const ats_vec3 g = ats_stretch_gradient(at(q, 0), at(q, 1), rest, k);
    Eigen::VectorXd out(6);
    out << g.x, g.y, g.z, -g.x, -g.y, -g.z;
    return out;
  }
  Eigen::MatrixXd hessian(const Eigen::VectorXd& q, bool project) const {
    const ats_mat3 h = ats_stretch_hessian(at(q, 0), at(q, 1), rest, k, project ? 1 : 0);
    Eigen::Matrix3d b;
    for (int r = 0; r < 3; ++r) b.row(r) << h.r[r].x, h.r[r].y, h.r[r].z;
    Eigen::MatrixXd out(6, 6);
    out << b, -b, -b, b;
    return out;
  }
};

struct RandomSprings {
  std::mt19937 rng{12345};
  std::uniform_real_distribution<double> unit{-1.0, 1.0};

  // Rest length 0.5x..1.5x the current one: stretched and compressed.
  std::pair<Spring, Eigen::VectorXd> next() {
    Eigen::VectorXd q(6);
    for (int i = 0; i < 6; ++i) q[i] = unit(rng);
    const double len = (q.head<3>() - q.tail<3>()).norm();
    Spring s{len * (1.0 + 0.5 * unit(rng)), std::pow(10.0, 2.0 * (unit(rng) + 1.0))};
    return {s, q};
  }
};

}  // namespace

TEST_CASE("stretch energy is 1/2 k (|xa - xb| - L)^2", "[energy][stretch]") {
  RandomSprings springs;
  for (int n = 0; n < 20; ++n) {
    const auto [s, q] = springs.next();
    const double c = (q.head<3>() - q.tail<3>()).norm() - s.rest;
    CHECK(s.energy(q) == Approx(0.5 * s.k * c * c).epsilon(1e-12));
  }
}

TEST_CASE("stretch gradient matches central finite differences of the energy", "[energy][stretch]") {
  RandomSprings springs;
  for (int n = 0; n < 50; ++n) {
    const auto [s, q] = springs.next();
    const Eigen::VectorXd g = s.gradient(q);
    const Eigen::VectorXd fd = atssim::test::fd_gradient([&](const Eigen::VectorXd& y) { return s.energy(y); }, q);
    INFO("spring " << n << " |g| " << g.norm() << " |g - fd| " << (g - fd).norm());
    CHECK((g - fd).norm() <= 1e-4 * g.norm() + 1e-9 * s.k);
  }
}

TEST_CASE("stretch Hessian matches finite differences of the gradient", "[energy][stretch]") {
  RandomSprings springs;
  for (int n = 0; n < 50; ++n) {
    const auto [s, q] = springs.next();
    const Eigen::MatrixXd H = s.hessian(q, false);
    const Eigen::MatrixXd fd = atssim::test::fd_jacobian([&](const Eigen::VectorXd& y) { return s.gradient(y); }, q);
    INFO("spring " << n << " |H| " << H.norm() << " |H - fd| " << (H - fd).norm());
    CHECK((H - fd).norm() <= 1e-4 * H.norm());
  }
}

TEST_CASE("the projected stretch Hessian is the exact Hessian with negative eigenvalues clamped to 0",
          "[energy][stretch]") {
  RandomSprings springs;
  int compressed = 0;
  for (int n = 0; n < 50; ++n) {
    const auto [s, q] = springs.next();
    compressed += (q.head<3>() - q.tail<3>()).norm() < s.rest;
    // Reference: eigen-decompose the exact 6x6 element Hessian and clamp.
    Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> eig(s.hessian(q, false));
    const Eigen::VectorXd clamped = eig.eigenvalues().cwiseMax(0.0);
    const Eigen::MatrixXd reference = eig.eigenvectors() * clamped.asDiagonal() * eig.eigenvectors().transpose();
    const Eigen::MatrixXd projected = s.hessian(q, true);
    CHECK((projected - reference).norm() <= 1e-10 * reference.norm());
  }
  CHECK(compressed > 10);  // the projection really had work to do
}

TEST_CASE("a spring at rest length, moved rigidly, has zero energy and zero force", "[energy][stretch]") {
  const Eigen::Vector3d a(0.3, -1.2, 0.7);
  const Eigen::Vector3d dir = Eigen::Vector3d(1.0, 2.0, -0.5).normalized();
  const double rest = 0.0625;
  Eigen::VectorXd q(6);
  q << a, a + rest * dir;
  const Spring s{rest, 1e4};
  CHECK(s.energy(q) <= 1e-24);
  CHECK(s.gradient(q).norm() <= 1e-10);
  // At rest only the axial stiffness k remains: eigenvalues {2k, 0, ...}.
  Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> eig(s.hessian(q, false));
  CHECK(eig.eigenvalues().maxCoeff() == Approx(2e4));
  CHECK(std::abs(eig.eigenvalues().minCoeff()) <= 1e-8);
}

TEST_CASE("a zero-length spring gives finite energy, gradient and Hessian", "[energy][stretch]") {
  const double length = GENERATE(0.0, 1e-30);
  Eigen::VectorXd q(6);
  q << 0.5, 0.25, -1.0, 0.5 + length, 0.25, -1.0;
  const Spring s{0.1, 1e4};
  CHECK(s.energy(q) == Approx(0.5 * 1e4 * (0.1 - length) * (0.1 - length)));
  CHECK(s.gradient(q).allFinite());
  CHECK(s.hessian(q, true).allFinite());
  CHECK(s.hessian(q, false).allFinite());
  // Collapsed completely, no direction is preferred: no force.
  if (length == 0.0) CHECK(s.gradient(q).norm() == 0.0);
}
