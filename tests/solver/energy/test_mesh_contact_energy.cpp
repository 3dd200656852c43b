#include <catch2/catch.hpp>

#include <cmath>
#include <random>
#include <vector>

#include "model/collider.hpp"
#include "solver/contact/collider_buffer.hpp"
#include "solver/energy/finite_differences.hpp"
#include "solver/energy/incremental_potential.hpp"
#include "solver/energy/potential_evaluation.hpp"
#include "support/obstacle_meshes.hpp"

using namespace atssim;
using Eigen::Vector3d;

TEST_CASE("the incremental potential holds a mesh obstacle's contact energy, with its gradient", "[contact][mesh]") {
  const test::SimpleMesh ball = test::obstacle_icosphere(0.2, 2);
  const Vector3d at(0.1, 0.5, -0.2);
  scene::ColliderDesc d;
  d.shape = scene::ColliderShape::mesh;
  d.mesh_vertices = ball.vertices;
  d.mesh_triangles = ball.triangles;
  d.point = {at.x(), at.y(), at.z()};
  d.thickness = 0.02;
  d.stiffness = 50.0;
  const solver::ColliderBuffer buffer = solver::collider_buffer(model::make_colliders({d}));

  // Particles just outside the ball, within its thickness, in random directions.
  solver::SimLayout layout;
  layout.colliders = buffer.records;
  layout.collider_count = buffer.count;
  std::mt19937 rng(2);
  std::normal_distribution<double> n(0.0, 1.0);
  std::uniform_real_distribution<double> depth(0.003, 0.017);
  const double mass = 0.01, h = 0.005;
  std::vector<double> expected_gap;
  for (int k = 0; k < 12; ++k) {
    const Vector3d dir = Vector3d(n(rng), n(rng), n(rng)).normalized();
    const Vector3d p = at + (0.2 + depth(rng)) * dir;
    layout.x.push_back({float(p.x()), float(p.y()), float(p.z()), float(1.0 / mass)});
    layout.v.push_back({});
  }
  const solver::energy::IncrementalPotential ip = solver::energy::make_incremental_potential(layout, layout.x, h);
  const Eigen::VectorXd x = solver::energy::positions_of(layout.x);

  // Independent: the brute-force distance to the placed triangles.
  double contact = 0.0;
  for (const auto& q : layout.x) {
    const double gap = test::mesh_distance(ball, at, Vector3d(q.x, q.y, q.z)) - d.thickness;
    if (gap < 0) contact += 0.5 * d.stiffness * mass / (h * h) * gap * gap;
  }
  REQUIRE(contact > 0.0);
  const solver::energy::EnergyTerms e = solver::energy::energy_terms(ip, x);
  CHECK(e.contact == Approx(contact).epsilon(1e-3));

  const Eigen::VectorXd g = solver::energy::gradient(ip, x);
  const Eigen::VectorXd fd =
      test::fd_gradient([&](const Eigen::VectorXd& y) { return solver::energy::total_energy(ip, y); }, x, 1e-7);
  CHECK((g - fd).norm() <= 1e-4 * fd.norm());
}
