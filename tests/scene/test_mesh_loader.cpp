#include <catch2/catch.hpp>

#include <fstream>

#include "scene/mesh_loader.hpp"
#include "support/temp_dir.hpp"
#include "util/error.hpp"

using namespace atssim;

TEST_CASE("an OBJ written here loads through assimp with the right counts") {
  test::TempDir dir;
  // A 3x3-vertex quad grid as 4 quads; assimp triangulates them into 8 triangles.
  std::string obj;
  for (int k = 0; k < 3; ++k) {
    for (int i = 0; i < 3; ++i) obj += "v " + std::to_string(i) + " 0 " + std::to_string(k) + "\n";
  }
  for (int k = 0; k < 2; ++k) {
    for (int i = 0; i < 2; ++i) {
      const int a = k * 3 + i + 1;
      obj += "f " + std::to_string(a) + " " + std::to_string(a + 1) + " " + std::to_string(a + 4) + " " +
             std::to_string(a + 3) + "\n";
    }
  }
  const auto mesh = scene::load_triangle_mesh(dir.write("grid.obj", obj), "test");
  CHECK(mesh.vertices.size() == 9);
  CHECK(mesh.triangles.size() == 8);
}

TEST_CASE("vertices split by UV seams are welded back together") {
  test::TempDir dir;
  // Two triangles sharing an edge, but with different texture coordinates.
  const std::string obj =
      "v 0 0 0\nv 1 0 0\nv 0 1 0\nv 1 1 0\n"
      "vt 0 0\nvt 1 0\nvt 0 1\nvt 1 1\nvt 0.5 0.5\nvt 0.25 0.25\n"
      "f 1/1 2/2 3/3\nf 2/5 4/4 3/6\n";
  const auto mesh = scene::load_triangle_mesh(dir.write("seam.obj", obj), "test");
  CHECK(mesh.vertices.size() == 4);
  CHECK(mesh.triangles.size() == 2);
}

TEST_CASE("an empty mesh file is an input error") {
  test::TempDir dir;
  CHECK_THROWS_AS(scene::load_triangle_mesh(dir.write("empty.obj", "# nothing\n"), "scene.yaml:3"), Error);
  try {
    scene::load_triangle_mesh(dir.write("points.obj", "v 0 0 0\nv 1 0 0\n"), "scene.yaml:3");
  } catch (const Error& e) {
    CHECK(e.exit_code() == 2);
    CHECK(std::string(e.what()).find("scene.yaml:3:") == 0);
  }
}
