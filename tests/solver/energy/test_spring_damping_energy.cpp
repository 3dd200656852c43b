// The springs' damping term of the incremental potential
// (kernels/common/energy_spring_damping.h): gradient and Hessian against
// finite differences, and its gradient is minus the explicit damping force
// at v = (x - x0)/h.
#include "solver/energy/element_math.hpp"  // first: the double instance of the shared math

#include <catch2/catch.hpp>

#include <random>

#include "solver/energy/finite_differences.hpp"

using namespace atssim::solver::energy::f64;

namespace {

ats_vec3 at(const Eigen::VectorXd& q, int i) { return ats_v3(q[3 * i], q[3 * i + 1], q[3 * i + 2]); }

}  // namespace

TEST_CASE("spring damping term: gradient and Hessian match finite differences, and -grad is the damping force",
          "[energy][spring_damping]") {
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> unit(-1.0, 1.0);
  for (int n = 0; n < 20; ++n) {
    Eigen::VectorXd q0(6), q(6);
    for (int i = 0; i < 6; ++i) {
      q0[i] = unit(rng);
      q[i] = q0[i] + 0.1 * unit(rng);
    }
    const double c = std::pow(10.0, 2.0 * unit(rng)), h = 1e-3;
    const double c_over_h = c / h;
    const auto energy = [&](const Eigen::VectorXd& y) {
      return ats_spring_damping_energy(at(y, 0), at(y, 1), at(q0, 0), at(q0, 1), c_over_h);
    };
    const auto gradient = [&](const Eigen::VectorXd& y) {
      const ats_vec3 g = ats_spring_damping_gradient(at(y, 0), at(y, 1), at(q0, 0), at(q0, 1), c_over_h);
      Eigen::VectorXd out(6);
      out << g.x, g.y, g.z, -g.x, -g.y, -g.z;
      return out;
    };
    const Eigen::VectorXd g = gradient(q), fd = atssim::test::fd_gradient(energy, q);
    CHECK((g - fd).norm() <= 1e-6 * (1.0 + g.norm()));
    const ats_mat3 hb = ats_spring_damping_hessian(at(q0, 0), at(q0, 1), c_over_h);
    Eigen::Matrix3d b;
    for (int r = 0; r < 3; ++r) b.row(r) << hb.r[r].x, hb.r[r].y, hb.r[r].z;
    Eigen::MatrixXd H(6, 6);
    H << b, -b, -b, b;
    const Eigen::MatrixXd J = atssim::test::fd_jacobian(gradient, q);
    CHECK((H - J).norm() <= 1e-6 * (1.0 + H.norm()));
    // The force c ((vb - va) . n0) n0 on a at v = (x - x0)/h (direction fixed at x0) is -grad_a.
    const ats_vec3 va = ats_scale(ats_sub(at(q, 0), at(q0, 0)), 1.0 / h);
    const ats_vec3 vb = ats_scale(ats_sub(at(q, 1), at(q0, 1)), 1.0 / h);
    const ats_vec3 f = ats_spring_damping_force(at(q0, 0), at(q0, 1), va, vb, c);
    CHECK(f.x == Approx(-g[0]).margin(1e-9 * (1.0 + g.norm())));
    CHECK(f.y == Approx(-g[1]).margin(1e-9 * (1.0 + g.norm())));
    CHECK(f.z == Approx(-g[2]).margin(1e-9 * (1.0 + g.norm())));
  }
}
