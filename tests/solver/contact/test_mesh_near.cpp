// A particle's near list of a mesh collider (kernels/common/mesh_near.h)
// against the tree walk it stands in for, and against brute force.
#include <catch2/catch.hpp>

#include <algorithm>
#include <bit>
#include <cstdint>
#include <random>
#include <set>
#include <vector>

#include "common/collider_distance.h"
#include "model/collider.hpp"
#include "solver/contact/collider_buffer.hpp"
#include "support/obstacle_meshes.hpp"

using namespace atssim;
using Eigen::Vector3d;

namespace {

scene::ColliderDesc mesh_desc(const test::SimpleMesh& m, const Vector3d& deg, const Vector3d& position,
                              double thickness) {
  return test::mesh_collider(m, {1, 1, 1}, deg, position, thickness);
}

ats_vec3 v3(const Vector3d& p) { return ats_v3(float(p.x()), float(p.y()), float(p.z())); }

bool same_bits(float a, float b) { return std::bit_cast<std::uint32_t>(a) == std::bit_cast<std::uint32_t>(b); }

// The world position of mesh vertex k of triangle t (in BVH leaf order, as the records hold them).
Vector3d corner(const std::vector<ats_collider_c>& records, int t, int k) {
  const ats_mesh_triangle* tris = ats_mesh_triangles(records.data());
  const ats_collider_c& c = records[0];
  Vector3d local(tris[t].p[3 * k], tris[t].p[3 * k + 1], tris[t].p[3 * k + 2]), w(c.c[0], c.c[1], c.c[2]);
  for (int a = 0; a < 3; ++a) w += local[a] * Vector3d(c.axes[4 * a], c.axes[4 * a + 1], c.axes[4 * a + 2]);
  return w;
}

struct Tally {
  int served = 0, touching = 0, overflowed = 0;
};

// Lists made at points near the mesh, then queried at points around them:
// wherever a list serves, its distance and normal are the walk's, bit for
// bit; a list holds every triangle brute force finds within its reach.
// The lists are made at centre + a x + b y + c z (the mesh's local axes),
// a, b, c uniform within `spread`.
Tally check_against_walk(const std::vector<ats_collider_c>& records, const Vector3d& centre, const Vector3d& spread,
                         int triangle_count, unsigned seed) {
  const ats_collider_c* c = records.data();
  const double reach = c->mesh[3], margin = ATS_MESH_NEAR_MARGIN * c->thickness;
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> u(-1, 1), m(-margin, margin);
  Tally tally;
  for (int k = 0; k < 400; ++k) {
    Vector3d x0 = centre;
    for (int a = 0; a < 3; ++a)
      x0 += spread[a] * u(rng) * Vector3d(c->axes[4 * a], c->axes[4 * a + 1], c->axes[4 * a + 2]);
    ats_mesh_near list{};
    ats_mesh_near_make(c, ats_mesh_local(c, v3(x0)), reach, &list);
    REQUIRE(list.margin == Approx(margin));
    if (list.count > ATS_MESH_NEAR_CAPACITY) {
      ++tally.overflowed;
      continue;
    }
    // every triangle within reach + margin, by brute force in double, is listed
    const std::set<int> listed(list.tri, list.tri + list.count);
    for (int t = 0; t < triangle_count; ++t) {
      const double d = test::triangle_distance(x0, corner(records, t, 0), corner(records, t, 1), corner(records, t, 2));
      if (d < reach + margin - 1e-6) CHECK(listed.count(t) == 1);
    }
    for (int j = 0; j < 8; ++j) {
      const Vector3d x = x0 + Vector3d(m(rng), m(rng), m(rng));
      const ats_surface_distance walk = ats_mesh_distance(c, v3(x), c->mesh[3]);
      const ats_surface_distance near = ats_mesh_distance_near(c, v3(x), c->mesh[3], &list);
      INFO("x0 " << x0.transpose() << " x " << x.transpose());
      CHECK(same_bits(walk.phi, near.phi));
      CHECK(same_bits(walk.n.x, near.n.x));
      CHECK(same_bits(walk.n.y, near.n.y));
      CHECK(same_bits(walk.n.z, near.n.z));
      if (ats_mesh_near_serves(&list, ats_mesh_local(c, v3(x)))) {
        ++tally.served;
        if (walk.phi < reach) ++tally.touching;
      }
    }
  }
  return tally;
}

}  // namespace

TEST_CASE("a near list of an open mesh gives the tree walk's distance and normal bit for bit where it serves") {
  const test::SimpleMesh sheet = test::sheet(1.0, 12);
  const Vector3d position(0.1, 0.5, -0.2);
  const std::vector<ats_collider_c> records =
      solver::collider_buffer(model::make_colliders({mesh_desc(sheet, {10, 30, 0}, position, 0.01)})).records;
  REQUIRE(records[0].mesh[2] == 0.0f);  // open
  const Tally t =
      check_against_walk(records, position, {0.45, 0.03, 0.45}, static_cast<int>(sheet.triangles.size()), 5);
  // Most queries are served from the list, many of them within the reach (contact).
  CHECK(t.served > 1500);
  CHECK(t.touching > 300);
  CHECK(t.overflowed < 40);
}

TEST_CASE("a near list of a closed mesh gives the tree walk's signed distance and normal bit for bit") {
  const test::SimpleMesh sphere = test::obstacle_icosphere(0.3, 2);
  const std::vector<ats_collider_c> records =
      solver::collider_buffer(model::make_colliders({mesh_desc(sphere, {0, 20, 0}, {0, 1, 0}, 0.01)})).records;
  REQUIRE(records[0].mesh[2] == 1.0f);  // closed: its reach is a quarter of its extent past the thickness
  const Tally t =
      check_against_walk(records, {0, 1, 0}, {0.35, 0.35, 0.35}, static_cast<int>(sphere.triangles.size()), 9);
  // The closed mesh's reach (0.16 m) holds more triangles than a list: those walk, and give the same.
  CHECK(t.overflowed > 100);
  CHECK(t.served > 100);
}

TEST_CASE("a particle's near list is kept within half its margin and made anew beyond it") {
  const test::SimpleMesh sheet = test::sheet(1.0, 12);
  const std::vector<ats_collider_c> records =
      solver::collider_buffer(model::make_colliders({mesh_desc(sheet, {0, 0, 0}, {0, 0, 0}, 0.01)})).records;
  const ats_collider_c* c = records.data();
  const double margin = ATS_MESH_NEAR_MARGIN * c->thickness;
  ats_mesh_near list{};
  ats_mesh_near_refresh(c, ats_v3(0.01f, 0.005f, 0.02f), &list);  // none yet: made
  CHECK(list.x0[0] == 0.01f);
  CHECK(list.count >= 1);
  ats_mesh_near_refresh(c, ats_v3(0.01f + float(0.45 * margin), 0.005f, 0.02f), &list);
  CHECK(list.x0[0] == 0.01f);  // kept
  const float moved = 0.01f + float(0.55 * margin);
  ats_mesh_near_refresh(c, ats_v3(moved, 0.005f, 0.02f), &list);
  CHECK(list.x0[0] == moved);  // made anew
  // and it serves up to (nearly) its margin, not beyond
  CHECK(ats_mesh_near_serves(&list, ats_v3(moved + float(0.98 * margin), 0.005f, 0.02f)));
  CHECK_FALSE(ats_mesh_near_serves(&list, ats_v3(moved + float(1.0 * margin), 0.005f, 0.02f)));
}

TEST_CASE("each mesh collider has its own slot among a particle's near lists, and every record counts them") {
  scene::ColliderDesc sphere;
  sphere.shape = scene::ColliderShape::sphere;
  sphere.radius = 0.2;
  sphere.thickness = 0.01;
  const test::SimpleMesh sheet = test::sheet(1.0, 4);
  const solver::ColliderBuffer b = solver::collider_buffer(model::make_colliders(
      {mesh_desc(sheet, {0, 0, 0}, {0, 0, 0}, 0.01), sphere, mesh_desc(sheet, {0, 0, 0}, {0, 1, 0}, 0.01)}));
  REQUIRE(b.count == 3);
  CHECK(b.records[0].near_slot == 0.0f);
  CHECK(b.records[2].near_slot == 1.0f);
  for (int i = 0; i < 3; ++i) CHECK(b.records[i].near_slots == 2.0f);
  ats_mesh_near lists[4] = {};
  CHECK(ats_near_of(b.records.data(), 3, lists, 1) == lists + 2);
}
