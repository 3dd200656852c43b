#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>
#include <random>
#include <vector>

#include <Eigen/Geometry>

#include "common/collider_distance.h"
#include "model/collider.hpp"
#include "solver/contact/collider_buffer.hpp"
#include "solver/contact/contact_summary.hpp"
#include "support/obstacle_meshes.hpp"

using namespace atssim;
using Eigen::Vector3d;

namespace {

struct WorldMesh {
  std::vector<Vector3d> v;
  std::vector<std::array<int, 3>> t;
};

// Placed as the scene would: scaled, rotated about x, then y, then z, moved.
WorldMesh place(const test::SimpleMesh& m, const Vector3d& scale, const Vector3d& deg, const Vector3d& position) {
  const double k = std::numbers::pi / 180.0;
  const Eigen::Matrix3d r =
      (Eigen::AngleAxisd(deg.z() * k, Vector3d::UnitZ()) * Eigen::AngleAxisd(deg.y() * k, Vector3d::UnitY()) *
       Eigen::AngleAxisd(deg.x() * k, Vector3d::UnitX()))
          .toRotationMatrix();
  WorldMesh w;
  for (const auto& p : m.vertices) w.v.push_back(r * Vector3d(p[0], p[1], p[2]).cwiseProduct(scale) + position);
  w.t = m.triangles;
  return w;
}

double unsigned_distance(const WorldMesh& m, const Vector3d& p) {
  double d = std::numeric_limits<double>::infinity();
  for (const auto& t : m.t) d = std::min(d, test::triangle_distance(p, m.v[t[0]], m.v[t[1]], m.v[t[2]]));
  return d;
}

// Inside a convex closed mesh: behind every face plane.
bool inside_convex(const WorldMesh& m, const Vector3d& p) {
  for (const auto& t : m.t) {
    const Vector3d n = (m.v[t[1]] - m.v[t[0]]).cross(m.v[t[2]] - m.v[t[0]]);
    if (n.dot(p - m.v[t[0]]) > 0) return false;
  }
  return true;
}

std::vector<ats_collider_c> mesh_records(const test::SimpleMesh& m, const Vector3d& scale, const Vector3d& deg,
                                         const Vector3d& position, double thickness) {
  const solver::ColliderBuffer b =
      solver::collider_buffer(model::make_colliders({test::mesh_collider(m, scale, deg, position, thickness)}));
  REQUIRE(b.count == 1);
  return b.records;
}

ats_surface_distance distance_of(const std::vector<ats_collider_c>& records, const Vector3d& p) {
  return ats_collider_distance(records.data(), ats_v3(float(p.x()), float(p.y()), float(p.z())));
}

Vector3d vec(ats_vec3 v) { return {v.x, v.y, v.z}; }

}  // namespace

TEST_CASE("the distance to a placed closed mesh is signed, matches brute force, and its normal leads to the surface") {
  const Vector3d scale(1.0, 0.6, 1.2), deg(30, 45, 10), position(0.2, 1.0, -0.3);
  const test::SimpleMesh sphere = test::obstacle_icosphere(0.3, 2);
  const WorldMesh world = place(sphere, scale, deg, position);
  const std::vector<ats_collider_c> records = mesh_records(sphere, scale, deg, position, 0.01);
  const double reach = records[0].mesh[3];
  REQUIRE(records[0].mesh[2] == 1.0f);  // closed
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> u(-0.5, 0.5);
  int near = 0, inside = 0;
  for (int k = 0; k < 3000; ++k) {
    const Vector3d p = position + Vector3d(u(rng), u(rng), u(rng));
    const double d = unsigned_distance(world, p);
    const bool in = inside_convex(world, p);
    const ats_surface_distance s = distance_of(records, p);
    if (d > 0.95 * reach) {
      if (d > 1.05 * reach) CHECK(s.phi == Approx(reach));  // out of reach: no contact
      continue;
    }
    ++near;
    inside += in;
    INFO("point " << p.transpose() << " distance " << d << " inside " << in);
    CHECK(s.phi == Approx(in ? -d : d).margin(2e-5));
    CHECK(vec(s.n).norm() == Approx(1.0).margin(1e-5));
    CHECK(unsigned_distance(world, p - double(s.phi) * vec(s.n)) < 2e-5);
  }
  CHECK(near > 300);
  CHECK(inside > 50);
}

TEST_CASE("the distance to an open mesh is unsigned on both sides and matches brute force") {
  const Vector3d scale(1, 1, 1), deg(0, 0, 20), position(0, 0.5, 0);
  const test::SimpleMesh s = test::sheet(1.0, 6);
  const WorldMesh world = place(s, scale, deg, position);
  const std::vector<ats_collider_c> records = mesh_records(s, scale, deg, position, 0.02);
  REQUIRE(records[0].mesh[2] == 0.0f);  // open
  const double reach = records[0].mesh[3];
  std::mt19937 rng(11);
  std::uniform_real_distribution<double> u(-0.6, 0.6), h(-0.04, 0.04);
  int near = 0;
  for (int k = 0; k < 3000; ++k) {
    const Vector3d p = position + Vector3d(u(rng), h(rng), u(rng));
    const double d = unsigned_distance(world, p);
    if (d > 0.95 * reach) continue;
    ++near;
    const ats_surface_distance sd = distance_of(records, p);
    CHECK(sd.phi == Approx(d).margin(2e-5));
    CHECK(unsigned_distance(world, p - double(sd.phi) * vec(sd.n)) < 2e-5);
  }
  CHECK(near > 300);
}

TEST_CASE("the contact record measures a mesh however far it is, the kernels see contact only within reach") {
  const test::SimpleMesh sphere = test::obstacle_icosphere(0.3, 1);
  const std::vector<ats_collider_c> records = mesh_records(sphere, {1, 1, 1}, {0, 0, 0}, {0, 0, 0}, 0.01);
  const std::vector<float> far{0.0f, 2.0f, 0.0f};
  const solver::ContactSummary s = solver::summarize_contacts(records, far, 1);
  // Nearest to (0, 2, 0): the vertex (0, 0.3, 0), the midpoint of the icosahedron's top edge pushed out
  // to the sphere by the subdivision.
  CHECK(s.min_distance == Approx(2.0 - 0.3 - 0.01).margin(1e-5));
  CHECK(s.active == 0);
  CHECK(ats_collider_gap(records.data(), ats_v3(0, 2, 0)).phi > 0);
}
