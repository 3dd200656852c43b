// Mass-spring cloth (issue #13, `model: springs`): the springs of a small
// grid and of a small triangle mesh against counts made by hand.
#include <catch2/catch.hpp>

#include <algorithm>

#include "model/cloth_builder.hpp"
#include "model/cloth_springs.hpp"
#include "scene/scene_loader.hpp"

using namespace atssim;

namespace {

bool contains(const std::vector<std::array<int, 2>>& pairs, int a, int b) {
  return std::find(pairs.begin(), pairs.end(), std::array<int, 2>{std::min(a, b), std::max(a, b)}) != pairs.end();
}

}  // namespace

TEST_CASE("cloth springs on a 4 x 3 grid: 17 structural, 12 shear, 10 bending (Provot)", "[cloth_springs]") {
  // Structural: 3 per row x 3 rows + 4 per column gap x 2 = 17; shear: 2 per
  // quad x 6 quads = 12; bending: 2 per row x 3 + 4 columns x 1 = 10.
  const model::ClothSprings s = model::grid_springs(4, 3);
  CHECK(s.structural.size() == 17);
  CHECK(s.shear.size() == 12);
  CHECK(s.bend.size() == 10);
  CHECK(contains(s.structural, 0, 1));
  CHECK(contains(s.structural, 0, 4));
  CHECK(contains(s.shear, 0, 5));
  CHECK(contains(s.shear, 1, 4));
  CHECK(contains(s.bend, 0, 2));
  CHECK(contains(s.bend, 0, 8));
  CHECK_FALSE(contains(s.bend, 0, 3));  // three apart: no spring
}

TEST_CASE("cloth springs on a triangulated 3 x 3 mesh: 16 edges, 8 shear, 7 bending", "[cloth_springs]") {
  // The mesh of a 3 x 3 grid (vertex k*3+i, each quad split along b-c), as
  // any triangle mesh: 12 grid-line edges and 4 diagonals (1-3, 2-4, 4-6,
  // 5-7). Interior edges: the 4 diagonals (opposite vertices 0-4, 1-5, 3-7,
  // 4-8) and 1-4, 4-7, 3-4, 4-5 (opposite 2-3, 5-6, 1-6, 2-7): 8 shear.
  // Bending, straight continuations within 30°: rows 0-2, 3-5, 6-8, columns
  // 0-6, 1-7, 2-8 and the one diagonal line of three, 2-4-6: 7.
  const scene::TriangleMesh mesh = model::make_grid_mesh({{1.0, 1.0}, {3, 3}});
  std::vector<Eigen::Vector3d> rest;
  for (const auto& v : mesh.vertices) rest.emplace_back(v[0], v[1], v[2]);
  const model::ClothSprings s = model::mesh_springs(rest, mesh.triangles);
  CHECK(s.structural.size() == 16);
  CHECK(s.shear.size() == 8);
  for (const auto& p : {std::array<int, 2>{0, 4}, {1, 5}, {3, 7}, {4, 8}, {2, 3}, {5, 6}, {1, 6}, {2, 7}}) {
    CHECK(contains(s.shear, p[0], p[1]));
  }
  CHECK(s.bend.size() == 7);
  for (const auto& p : {std::array<int, 2>{0, 2}, {3, 5}, {6, 8}, {0, 6}, {1, 7}, {2, 8}, {2, 6}}) {
    CHECK(contains(s.bend, p[0], p[1]));
  }
}

TEST_CASE("a cloth with model: springs has exactly its springs as stretch elements, with their stiffnesses",
          "[cloth_springs]") {
  const auto scene = scene::parse_scene(
      "objects:\n"
      "  - grid: {size: [1, 1], resolution: [4, 3]}\n"
      "    material: {model: springs, stretch_stiffness: 100, shear_stiffness: 50, bend_spring_stiffness: 10,\n"
      "               damping: 0.002}\n",
      "s.yaml", ".");
  const model::Model m = model::build_model(scene);
  REQUIRE(m.stretch.size() == 17 + 12 + 10);
  CHECK(m.bend.size() == 0);
  int k100 = 0, k50 = 0, k10 = 0;
  for (std::size_t e = 0; e < m.stretch.size(); ++e) {
    const double k = 1.0 / m.stretch.compliance[e];
    k100 += k == Approx(100.0);
    k50 += k == Approx(50.0);
    k10 += k == Approx(10.0);
    CHECK(m.stretch.damping[e] == 0.002);
  }
  CHECK(k100 == 17);
  CHECK(k50 == 12);
  CHECK(k10 == 10);
}

TEST_CASE("shear_stiffness without model: springs, and an unknown cloth model, are input errors", "[cloth_springs]") {
  CHECK_THROWS_WITH(scene::parse_scene("objects:\n  - grid: {resolution: [4, 4]}\n"
                                       "    material: {stretch_stiffness: 100, shear_stiffness: 5}\n",
                                       "s.yaml", "."),
                    Catch::Contains("add 'model: springs'"));
  CHECK_THROWS_WITH(scene::parse_scene("objects:\n  - grid: {resolution: [4, 4]}\n"
                                       "    material: {model: spring}\n",
                                       "s.yaml", "."),
                    Catch::Contains("did you mean 'springs'"));
}
