#include <catch2/catch.hpp>

#include <algorithm>
#include <random>

#include "model/obstacle_mesh.hpp"

using namespace atssim;
using Eigen::Vector3d;

namespace {

const std::vector<std::array<double, 3>> kTetVertices{{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0, 0, 1}};
const std::vector<std::array<int, 3>> kTetOutward{{0, 2, 1}, {0, 1, 3}, {0, 3, 2}, {1, 2, 3}};

// A grid of n x n quads in the xz plane, two triangles each: an open mesh.
void sheet(int n, std::vector<std::array<double, 3>>& v, std::vector<std::array<int, 3>>& t) {
  for (int i = 0; i <= n; ++i) {
    for (int j = 0; j <= n; ++j) v.push_back({double(i), 0.0, double(j)});
  }
  for (int i = 0; i < n; ++i) {
    for (int j = 0; j < n; ++j) {
      const int a = i * (n + 1) + j, b = a + 1, c = a + n + 1, d = c + 1;
      t.push_back({a, b, d});
      t.push_back({a, d, c});
    }
  }
}

bool contains(const model::BvhNode& n, const Vector3d& p) {
  return (p.array() >= n.lo.array() - 1e-12).all() && (p.array() <= n.hi.array() + 1e-12).all();
}

}  // namespace

TEST_CASE("a tetrahedron is closed and turned outward, a sheet is open") {
  const model::ObstacleMesh out = model::make_obstacle_mesh(kTetVertices, kTetOutward, {1, 1, 1});
  CHECK(out.closed);
  std::vector<std::array<int, 3>> inward = kTetOutward;
  for (auto& t : inward) std::swap(t[1], t[2]);
  const model::ObstacleMesh turned = model::make_obstacle_mesh(kTetVertices, inward, {1, 1, 1});
  REQUIRE(turned.closed);
  // The face x + y + z = 1 faces away from the origin once turned outward.
  for (std::size_t i = 0; i < turned.triangles.size(); ++i) {
    const Vector3d centroid = (turned.vertices[turned.triangles[i][0]] + turned.vertices[turned.triangles[i][1]] +
                               turned.vertices[turned.triangles[i][2]]) /
                              3.0;
    CHECK(turned.face_normal[i].dot(centroid - Vector3d(0.25, 0.25, 0.25)) > 0.0);
  }
  std::vector<std::array<double, 3>> v;
  std::vector<std::array<int, 3>> t;
  sheet(3, v, t);
  CHECK_FALSE(model::make_obstacle_mesh(v, t, {1, 1, 1}).closed);
  // A tetrahedron missing a face is open.
  CHECK_FALSE(model::make_obstacle_mesh(kTetVertices, {kTetOutward.begin(), kTetOutward.end() - 1}, {1, 1, 1}).closed);
}

TEST_CASE("the BVH holds every triangle in exactly one leaf, inside the boxes of the leaf and its ancestors") {
  std::vector<std::array<double, 3>> v;
  std::vector<std::array<int, 3>> t;
  sheet(12, v, t);
  const model::ObstacleMesh m = model::make_obstacle_mesh(v, t, {0.5, 1, 2});
  const model::ObstacleBvh& bvh = m.bvh;
  std::vector<int> seen(m.triangles.size(), 0);
  std::vector<int> parent(bvh.nodes.size(), -1);
  for (std::size_t i = 0; i < bvh.nodes.size(); ++i) {
    const auto& n = bvh.nodes[i];
    if (n.count == 0) {
      REQUIRE(n.first > static_cast<int>(i));
      parent[n.first] = parent[n.first + 1] = static_cast<int>(i);
    }
  }
  for (std::size_t i = 0; i < bvh.nodes.size(); ++i) {
    const auto& n = bvh.nodes[i];
    if (n.count == 0) continue;
    CHECK(n.count <= 4);
    for (int k = n.first; k < n.first + n.count; ++k) {
      const int tri = bvh.order[k];
      ++seen[tri];
      for (int corner : m.triangles[tri]) {
        for (int a = static_cast<int>(i); a >= 0; a = parent[a]) CHECK(contains(bvh.nodes[a], m.vertices[corner]));
      }
    }
  }
  CHECK(std::all_of(seen.begin(), seen.end(), [](int s) { return s == 1; }));
}

TEST_CASE("refitting the BVH after the vertices moved gives the boxes of a rebuild's root") {
  std::vector<std::array<double, 3>> v;
  std::vector<std::array<int, 3>> t;
  sheet(10, v, t);
  model::ObstacleMesh m = model::make_obstacle_mesh(v, t, {1, 1, 1});
  std::mt19937 rng(3);
  std::uniform_real_distribution<double> jitter(-0.3, 0.3);
  for (Vector3d& p : m.vertices) p += Vector3d(jitter(rng), jitter(rng), jitter(rng));
  model::refit_bvh(m.bvh, m.vertices, m.triangles);
  const model::ObstacleBvh fresh = model::build_bvh(m.vertices, m.triangles);
  CHECK((m.bvh.nodes[0].lo - fresh.nodes[0].lo).norm() < 1e-12);
  CHECK((m.bvh.nodes[0].hi - fresh.nodes[0].hi).norm() < 1e-12);
  for (const auto& n : m.bvh.nodes) {
    if (n.count == 0) continue;
    for (int k = n.first; k < n.first + n.count; ++k) {
      for (int corner : m.triangles[m.bvh.order[k]]) CHECK(contains(n, m.vertices[corner]));
    }
  }
}
