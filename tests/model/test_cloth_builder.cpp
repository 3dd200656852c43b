#include <catch2/catch.hpp>

#include <numeric>

#include "model/cloth_builder.hpp"
#include "scene/scene_loader.hpp"
#include "support/scenes.hpp"
#include "util/error.hpp"

using namespace atssim;

TEST_CASE("a grid has nx*nz vertices, 2(nx-1)(nz-1) triangles and the expected edges") {
  const auto mesh = model::make_grid_mesh({{2.0, 1.0}, {5, 4}});
  CHECK(mesh.vertices.size() == 20);
  CHECK(mesh.triangles.size() == 24);
  // structural (4*4 + 5*3) + one diagonal per quad (12)
  CHECK(model::unique_edges(mesh.triangles).size() == 16 + 15 + 12);
  // interior edges = all edges - boundary edges (2*(4+3))
  CHECK(model::bending_stencils(mesh.triangles).size() == 43 - 14);
}

TEST_CASE("lumped masses add up to density times area") {
  const auto scene = scene::parse_scene(test::hanging_cloth_yaml(9), "s.yaml", ".");
  const auto m = model::build_model(scene);
  const double total = std::accumulate(m.particles.mass.begin(), m.particles.mass.end(), 0.0);
  CHECK(total == Approx(0.2 * 1.0 * 1.0).epsilon(1e-12));
}

TEST_CASE("pin boxes give inverse mass zero to exactly the corners") {
  const auto m = model::build_model(scene::parse_scene(test::hanging_cloth_yaml(9), "s.yaml", "."));
  int pinned = 0;
  for (std::size_t i = 0; i < m.particles.size(); ++i) {
    if (m.particles.inv_mass[i] == 0.0) {
      ++pinned;
      CHECK(m.particles.position[i].z() == Approx(-0.5));
      CHECK(std::abs(m.particles.position[i].x()) == Approx(0.5));
    }
  }
  CHECK(pinned == 2);
  CHECK(m.objects[0].pinned.size() == 2);
}

TEST_CASE("only the element sets the material asks for exist") {
  auto m = model::build_model(scene::parse_scene(test::hanging_cloth_yaml(5, 1e4, 0.0), "s.yaml", "."));
  CHECK(m.stretch.size() > 0);
  CHECK(m.bend.size() == 0);
  m = model::build_model(scene::parse_scene(test::hanging_cloth_yaml(5, 0.0, 1e-3), "s.yaml", "."));
  CHECK(m.stretch.size() == 0);
  CHECK(m.bend.size() > 0);
}

TEST_CASE("isometric bending weights vanish on a flat sheet and sum to zero") {
  const std::string yaml =
      "objects:\n  - grid: {size: [1, 0.7], resolution: [6, 5]}\n"
      "    transform: {rotate: [30, 10, 45], translate: [1, 2, 3]}\n"
      "    material: {bend_stiffness: 1}\n";
  const auto scene = scene::parse_scene(yaml, "s.yaml", ".");
  const auto m = model::build_model(scene);
  REQUIRE(m.bend.size() > 0);
  for (std::size_t s = 0; s < m.bend.size(); ++s) {
    const auto& K = m.bend.weights[s];
    CHECK(K[0] + K[1] + K[2] + K[3] == Approx(0.0).margin(1e-9));
    model::Vec3 c = model::Vec3::Zero();
    for (int i = 0; i < 4; ++i) c += K[i] * m.particles.position[m.bend.stencils[s][i]];
    CHECK(c.norm() == Approx(0.0).margin(1e-9));
  }
}

TEST_CASE("an out-of-range pinned vertex is an input error naming the object's line") {
  const std::string yaml =
      "objects:\n"
      "  - name: small\n"
      "    grid: {size: [1, 1], resolution: [3, 3]}\n"
      "    pins: {vertices: [0, 9]}\n";
  try {
    model::build_model(scene::parse_scene(yaml, "s.yaml", "."));
    FAIL("expected an error");
  } catch (const Error& e) {
    CHECK(e.exit_code() == 2);
    CHECK(std::string(e.what()).find("s.yaml:2:") == 0);
    CHECK(std::string(e.what()).find("pinned vertex 9") != std::string::npos);
  }
}
