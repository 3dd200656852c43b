// The 3x3 eigen-clamp (ats_m3_project_psd, kernels/common/energy_mat3.h)
// against Eigen's symmetric eigensolver, in double.
#include "solver/energy/element_math.hpp"  // first: the double instance of the shared math

#include <catch2/catch.hpp>

#include <random>

#include <Eigen/Eigenvalues>

#include "solver/energy/element_checks.hpp"

using namespace atssim;
using namespace atssim::solver::energy::f64;

namespace {

Eigen::Matrix3d projected(const Eigen::Matrix3d& m) {
  return test::ElementFunctions::to_eigen(ats_m3_project_psd(test::to_ats(m)));
}

}  // namespace

TEST_CASE("project_psd clamps the negative eigenvalues of a symmetric 3x3 at 0", "[energy][psd]") {
  std::mt19937 rng(41);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  for (int n = 0; n < 200; ++n) {
    const Eigen::Matrix3d R = test::random_rotation(rng);
    // Spread of magnitudes, repeated eigenvalues sometimes.
    Eigen::Vector3d l(u(rng), u(rng), std::pow(10.0, 3 * u(rng)) * u(rng));
    if (n % 10 == 0) l[1] = l[0];
    const Eigen::Matrix3d m = R * l.asDiagonal() * R.transpose();
    const Eigen::Matrix3d expected = R * l.cwiseMax(0.0).asDiagonal() * R.transpose();
    INFO("eigenvalues " << l.transpose());
    CHECK((projected(m) - expected).norm() <= 1e-12 * m.norm());
  }
}

TEST_CASE("project_psd leaves PSD matrices alone and zeroes NSD ones", "[energy][psd]") {
  std::mt19937 rng(42);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  for (int n = 0; n < 50; ++n) {
    Eigen::Matrix3d a;
    for (int i = 0; i < 9; ++i) a(i / 3, i % 3) = u(rng);
    const Eigen::Matrix3d psd = a * a.transpose();
    CHECK((projected(psd) - psd).norm() <= 1e-12 * psd.norm());
    CHECK(projected(-psd).norm() <= 1e-12 * psd.norm());
  }
  CHECK(projected(Eigen::Matrix3d::Zero()).norm() == 0.0);
  const Eigen::Matrix3d d = Eigen::Vector3d(2.0, -1.0, 3.0).asDiagonal();
  CHECK((projected(d) - Eigen::Matrix3d(Eigen::Vector3d(2.0, 0.0, 3.0).asDiagonal())).norm() == 0.0);
}
