// StVK membrane triangles (kernels/common/energy_membrane_stvk.h) in double.
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

struct Membrane {
  ats_membrane_rest rest{};
  double mu = 1.0, lambda = 0.5;

  ElementFunctions functions() const {
    const ats_mat2 dm = rest.dm_inv;
    const double A = rest.area, m = mu, l = lambda;
    ElementFunctions f;
    f.vertices = 3;
    f.energy = [=](const ats_vec3* x) { return ats_membrane_stvk_energy(x, dm, A, m, l); };
    f.gradient = [=](const ats_vec3* x, int a) { return ats_membrane_stvk_gradient(x, dm, A, m, l, a); };
    f.hessian = [=](const ats_vec3* x, int a, int b) { return ats_membrane_stvk_hessian(x, dm, A, m, l, a, b); };
    return f;
  }
};

// A random triangle in 3D, not too thin.
std::vector<Eigen::Vector3d> random_rest_triangle(std::mt19937& rng) {
  std::uniform_real_distribution<double> u(-0.2, 0.2);
  std::vector<Eigen::Vector3d> x = {{0, 0, 0}, {1, 0, 0}, {0.3, 0.9, 0}};
  for (auto& p : x) p += Eigen::Vector3d(u(rng), u(rng), u(rng));
  const Eigen::Matrix3d R = test::random_rotation(rng);
  for (auto& p : x) p = R * p;
  return x;
}

Membrane random_membrane(std::mt19937& rng, const std::vector<Eigen::Vector3d>& rest) {
  std::uniform_real_distribution<double> u(0.5, 1.5);
  Membrane m;
  m.mu = u(rng);
  m.lambda = u(rng);
  const auto xr = test::to_ats(rest);
  m.rest = ats_membrane_rest_of(xr.data());
  return m;
}

}  // namespace

TEST_CASE("the membrane rest frame reproduces the rest area and F = identity on the plane", "[energy][membrane]") {
  std::mt19937 rng(21);
  const auto rest = random_rest_triangle(rng);
  const auto xr = test::to_ats(rest);
  const ats_membrane_rest r = ats_membrane_rest_of(xr.data());
  CHECK(r.area == Approx(0.5 * (rest[1] - rest[0]).cross(rest[2] - rest[0]).norm()).epsilon(1e-12));
  const ats_mat32 F = ats_membrane_deformation(xr.data(), r.dm_inv);
  CHECK(ats_dot(F.c[0], F.c[0]) == Approx(1.0).epsilon(1e-12));
  CHECK(ats_dot(F.c[1], F.c[1]) == Approx(1.0).epsilon(1e-12));
  CHECK(std::abs(ats_dot(F.c[0], F.c[1])) <= 1e-12);
}

TEST_CASE("membrane gradient matches central finite differences", "[energy][membrane]") {
  std::mt19937 rng(22);
  for (int n = 0; n < 50; ++n) {
    const auto rest = random_rest_triangle(rng);
    const ElementFunctions f = random_membrane(rng, rest).functions();
    const Eigen::VectorXd q = test::pack(test::random_deformation(rng, rest));
    const Eigen::VectorXd g = f.gradient_at(q);
    const Eigen::VectorXd fd = test::fd_gradient([&](const Eigen::VectorXd& y) { return f.energy_at(y); }, q);
    INFO("element " << n << " |g| " << g.norm() << " |g - fd| " << (g - fd).norm());
    CHECK((g - fd).norm() <= 1e-4 * g.norm());
  }
}

TEST_CASE("membrane Hessian blocks match finite differences of the gradient and are symmetric", "[energy][membrane]") {
  std::mt19937 rng(23);
  for (int n = 0; n < 50; ++n) {
    const auto rest = random_rest_triangle(rng);
    const ElementFunctions f = random_membrane(rng, rest).functions();
    const Eigen::VectorXd q = test::pack(test::random_deformation(rng, rest));
    const Eigen::MatrixXd H = f.hessian_at(q);
    const Eigen::MatrixXd fd = test::fd_jacobian([&](const Eigen::VectorXd& y) { return f.gradient_at(y); }, q);
    INFO("element " << n << " |H| " << H.norm() << " |H - fd| " << (H - fd).norm());
    CHECK((H - fd).norm() <= 1e-4 * H.norm());
    CHECK((H - H.transpose()).norm() <= 1e-12 * H.norm());
  }
}

TEST_CASE("a membrane at rest, moved rigidly, has zero energy and zero force", "[energy][membrane]") {
  std::mt19937 rng(24);
  for (int n = 0; n < 20; ++n) {
    const auto rest = random_rest_triangle(rng);
    const Membrane m = random_membrane(rng, rest);
    const ElementFunctions f = m.functions();
    const Eigen::Matrix3d R = test::random_rotation(rng);
    for (bool moved : {false, true}) {
      std::vector<Eigen::Vector3d> x = rest;
      if (moved) {
        for (auto& p : x) p = R * p + Eigen::Vector3d(0.3, -2.0, 1.5);
      }
      const Eigen::VectorXd q = test::pack(x);
      INFO("element " << n << (moved ? " moved" : " at rest"));
      CHECK(std::abs(f.energy_at(q)) <= 1e-12 * m.mu * m.rest.area);
      CHECK(f.gradient_at(q).norm() <= 1e-12 * m.mu * std::sqrt(m.rest.area));  // mu A |b|, |b| ~ A^-1/2
    }
  }
}

TEST_CASE("membrane energy is unchanged by a rotation of the deformed shape", "[energy][membrane]") {
  std::mt19937 rng(25);
  for (int n = 0; n < 20; ++n) {
    const auto rest = random_rest_triangle(rng);
    const ElementFunctions f = random_membrane(rng, rest).functions();
    const auto x = test::random_deformation(rng, rest);
    const Eigen::Matrix3d R = test::random_rotation(rng);
    std::vector<Eigen::Vector3d> rx;
    for (const auto& p : x) rx.push_back(R * p);
    CHECK(f.energy_at(test::pack(rx)) == Approx(f.energy_at(test::pack(x))).epsilon(1e-12));
  }
}

TEST_CASE("at small in-plane strain the membrane energy equals linear plane elasticity", "[energy][membrane]") {
  std::mt19937 rng(26);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  for (int n = 0; n < 10; ++n) {
    const auto rest = random_rest_triangle(rng);
    const Membrane m = random_membrane(rng, rest);
    // A symmetric strain in the plane of the rest triangle: eps = sum e_i e_j^T eps2_ij.
    const Eigen::Vector3d e1 = (rest[1] - rest[0]).normalized();
    const Eigen::Vector3d e2 = (rest[1] - rest[0]).cross(rest[2] - rest[0]).cross(e1).normalized();
    Eigen::Matrix2d eps2;
    eps2 << u(rng), u(rng), 0, u(rng);
    eps2(1, 0) = eps2(0, 1);
    eps2 *= 1e-4;
    Eigen::Matrix<double, 3, 2> B;
    B << e1, e2;
    const Eigen::Matrix3d eps = B * eps2 * B.transpose();
    std::vector<Eigen::Vector3d> x;
    for (const auto& p : rest) x.push_back(p + eps * (p - rest[0]));
    const double linear = m.rest.area * (m.mu * eps2.squaredNorm() + 0.5 * m.lambda * eps2.trace() * eps2.trace());
    CHECK(m.functions().energy_at(test::pack(x)) == Approx(linear).epsilon(1e-3));
  }
}

TEST_CASE("membrane PSD diagonal blocks have no negative eigenvalue, also under compression", "[energy][membrane]") {
  std::mt19937 rng(27);
  int clamped = 0;
  for (int n = 0; n < 50; ++n) {
    const auto rest = random_rest_triangle(rng);
    const Membrane m = random_membrane(rng, rest);
    std::vector<Eigen::Vector3d> xe = test::random_deformation(rng, rest, 0.3);
    if (n % 2 == 0) {
      for (auto& p : xe) p *= 0.6;  // compressed
    }
    const auto x = test::to_ats(xe);
    for (int a = 0; a < 3; ++a) {
      const Eigen::Matrix3d h = ElementFunctions::to_eigen(
          ats_membrane_stvk_hessian(x.data(), m.rest.dm_inv, m.rest.area, m.mu, m.lambda, a, a));
      const Eigen::Matrix3d p = ElementFunctions::to_eigen(
          ats_membrane_stvk_hessian_diag_psd(x.data(), m.rest.dm_inv, m.rest.area, m.mu, m.lambda, a));
      Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> eh(h), ep(p);
      CHECK(ep.eigenvalues().minCoeff() >= -1e-12 * h.norm());
      if (eh.eigenvalues().minCoeff() < 0) ++clamped;
    }
  }
  CHECK(clamped > 0);
}
