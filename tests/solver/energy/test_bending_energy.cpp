#include "solver/energy/element_math.hpp"  // first: the double instance of the shared math

#include <catch2/catch.hpp>

#include <random>

#include <Eigen/Eigenvalues>
#include <Eigen/Geometry>

#include "model/cloth_builder.hpp"
#include "scene/scene_loader.hpp"
#include "solver/energy/finite_differences.hpp"

using namespace atssim;
using namespace atssim::solver::energy::f64;

namespace {

// One isometric bending stencil as a function of its 12 coordinates.
struct Stencil {
  double K[4] = {0, 0, 0, 0};
  double scale = 1.0;
  double k = 1.0;

  static void at(const Eigen::VectorXd& q, ats_vec3 x[4]) {
    for (int i = 0; i < 4; ++i) x[i] = ats_v3(q[3 * i], q[3 * i + 1], q[3 * i + 2]);
  }
  double energy(const Eigen::VectorXd& q) const {
    ats_vec3 x[4];
    at(q, x);
    return ats_bend_energy(x, K, scale, k);
  }
  Eigen::VectorXd gradient(const Eigen::VectorXd& q) const {
    ats_vec3 x[4];
    at(q, x);
    Eigen::VectorXd out(12);
    for (int i = 0; i < 4; ++i) {
      const ats_vec3 g = ats_bend_gradient(x, K, scale, k, i);
      out.segment<3>(3 * i) << g.x, g.y, g.z;
    }
    return out;
  }
  Eigen::MatrixXd hessian() const {
    Eigen::MatrixXd out(12, 12);
    for (int i = 0; i < 4; ++i) {
      for (int j = 0; j < 4; ++j) {
        const ats_mat3 h = ats_bend_hessian(K, scale, k, i, j);
        for (int r = 0; r < 3; ++r) out.block<1, 3>(3 * i + r, 3 * j) << h.r[r].x, h.r[r].y, h.r[r].z;
      }
    }
    return out;
  }
};

struct RandomStencils {
  std::mt19937 rng{777};
  std::uniform_real_distribution<double> unit{-1.0, 1.0};

  std::pair<Stencil, Eigen::VectorXd> next() {
    Stencil s;
    for (double& w : s.K) w = 2.0 * unit(rng);
    s.scale = 10.0 * (1.5 + unit(rng));
    s.k = 1e-3 * (1.5 + unit(rng));
    Eigen::VectorXd q(12);
    for (int i = 0; i < 12; ++i) q[i] = unit(rng);
    return {s, q};
  }
};

model::Model flat_cloth() {
  const std::string yaml =
      "objects:\n  - grid: {size: [1, 0.5], resolution: [5, 4]}\n"
      "    material: {density: 0.2, bend_stiffness: 1e-3}\n";
  return model::build_model(scene::parse_scene(yaml, "s.yaml", "."));
}

}  // namespace

TEST_CASE("bending energy is 1/2 k s |sum K_i x_i|^2", "[energy][bend]") {
  RandomStencils stencils;
  for (int n = 0; n < 20; ++n) {
    const auto [s, q] = stencils.next();
    Eigen::Vector3d sum = Eigen::Vector3d::Zero();
    for (int i = 0; i < 4; ++i) sum += s.K[i] * q.segment<3>(3 * i);
    CHECK(s.energy(q) == Approx(0.5 * s.k * s.scale * sum.squaredNorm()).epsilon(1e-12));
  }
}

TEST_CASE("bending gradient matches central finite differences of the energy", "[energy][bend]") {
  RandomStencils stencils;
  for (int n = 0; n < 50; ++n) {
    const auto [s, q] = stencils.next();
    const Eigen::VectorXd g = s.gradient(q);
    const Eigen::VectorXd fd = atssim::test::fd_gradient([&](const Eigen::VectorXd& y) { return s.energy(y); }, q);
    INFO("stencil " << n << " |g| " << g.norm() << " |g - fd| " << (g - fd).norm());
    CHECK((g - fd).norm() <= 1e-4 * g.norm());
  }
}

TEST_CASE("bending Hessian matches finite differences of the gradient", "[energy][bend]") {
  RandomStencils stencils;
  for (int n = 0; n < 50; ++n) {
    const auto [s, q] = stencils.next();
    const Eigen::MatrixXd H = s.hessian();
    const Eigen::MatrixXd fd = atssim::test::fd_jacobian([&](const Eigen::VectorXd& y) { return s.gradient(y); }, q);
    INFO("stencil " << n << " |H| " << H.norm() << " |H - fd| " << (H - fd).norm());
    CHECK((H - fd).norm() <= 1e-4 * H.norm());
  }
}

TEST_CASE("a flat cloth, moved rigidly, has zero bending energy and zero bending force", "[energy][bend]") {
  const model::Model m = flat_cloth();
  REQUIRE(m.bend.size() > 10);
  const Eigen::Matrix3d R = Eigen::AngleAxisd(0.7, Eigen::Vector3d(1, 2, 3).normalized()).toRotationMatrix();
  const Eigen::Vector3d t(0.3, -2.0, 1.5);
  for (bool moved : {false, true}) {
    for (std::size_t e = 0; e < m.bend.size(); ++e) {
      Stencil s;
      for (int i = 0; i < 4; ++i) s.K[i] = m.bend.weights[e][i];
      s.scale = m.bend.scale[e];
      s.k = 1.0 / m.bend.compliance[e];
      Eigen::VectorXd q(12);
      for (int i = 0; i < 4; ++i) {
        const Eigen::Vector3d x = m.particles.position[m.bend.stencils[e][i]];
        q.segment<3>(3 * i) = moved ? Eigen::Vector3d(R * x + t) : x;
      }
      INFO("stencil " << e << (moved ? " moved" : " at rest"));
      // Scale of a force here: k s |K| |x| ~ k s.
      CHECK(s.energy(q) <= 1e-24 * s.k * s.scale);
      CHECK(s.gradient(q).norm() <= 1e-12 * s.k * s.scale);
    }
  }
}

TEST_CASE("the bending Hessian is positive semi-definite without projection", "[energy][bend]") {
  RandomStencils stencils;
  for (int n = 0; n < 20; ++n) {
    const Eigen::MatrixXd H = stencils.next().first.hessian();
    Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> eig(H);
    CHECK(eig.eigenvalues().minCoeff() >= -1e-12 * H.norm());
  }
}
