#include <catch2/catch.hpp>

#include <string>

#include "scene/scene_loader.hpp"
#include "support/temp_dir.hpp"
#include "util/error.hpp"

using namespace atssim;

namespace {

const std::string kCloth =
    "objects:\n"
    "  - grid: {size: [1, 1], resolution: [4, 4]}\n"
    "    material: {stretch_stiffness: 100}\n"
    "colliders:\n";  // the first collider is on line 5

const std::string kTetrahedron =
    "v 0 0 0\nv 1 0 0\nv 0 1 0\nv 0 0 1\n"
    "f 1 3 2\nf 1 2 4\nf 1 4 3\nf 2 3 4\n";

std::string error_of(const test::TempDir& dir, const std::string& colliders) {
  try {
    scene::parse_scene(kCloth + colliders, "scene.yaml", dir.path().string());
  } catch (const Error& e) {
    CHECK(e.exit_code() == 2);
    return e.what();
  }
  return "";
}

}  // namespace

TEST_CASE("a mesh collider is loaded relative to the scene's folder, with scale, position and rotation") {
  test::TempDir dir;
  dir.write("tet.obj", kTetrahedron);
  const auto s = scene::parse_scene(kCloth +
                                        "  - {type: mesh, file: tet.obj, scale: 2, position: [0, 1, 0],\n"
                                        "     rotation: [0, 90, 0], thickness: 0.01, friction: 0.5}\n"
                                        "  - {type: mesh, file: tet.obj, scale: [1, 2, 3], velocity: [0, 0, 1]}\n",
                                    "scene.yaml", dir.path().string());
  REQUIRE(s.colliders.size() == 2);
  const auto& c = s.colliders[0];
  CHECK(c.shape == scene::ColliderShape::mesh);
  CHECK(c.mesh_vertices.size() == 4);
  CHECK(c.mesh_triangles.size() == 4);
  CHECK(c.scale[1] == 2.0);
  CHECK(c.point[1] == 1.0);
  CHECK(c.rotate_deg[1] == 90.0);
  CHECK(c.static_friction == 0.5);
  CHECK(s.colliders[1].scale[2] == 3.0);
  CHECK(s.colliders[1].motion.kind == scene::MotionKind::velocity);
}

TEST_CASE("a missing, empty or triangle-less obstacle mesh, or a bad scale, stops with the line and exit code 2") {
  test::TempDir dir;
  dir.write("empty.obj", "");
  dir.write("points.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\n");
  dir.write("tet.obj", kTetrahedron);
  CHECK_THAT(error_of(dir, "  - {type: mesh, file: nowhere.obj}\n"), Catch::Contains("scene.yaml:5"));
  CHECK_THAT(error_of(dir, "  - {type: mesh, file: empty.obj}\n"), Catch::Contains("scene.yaml:5"));
  CHECK_THAT(error_of(dir, "  - {type: mesh, file: points.obj}\n"), Catch::Contains("scene.yaml:5"));
  CHECK_THAT(error_of(dir, "  - {type: mesh}\n"), Catch::Contains("scene.yaml:5") && Catch::Contains("'file'"));
  CHECK_THAT(error_of(dir, "  - {type: mesh, file: tet.obj, scale: 0}\n"),
             Catch::Contains("scene.yaml:5") && Catch::Contains("scale"));
  CHECK_THAT(error_of(dir, "  - {type: mesh, file: tet.obj, radius: 1}\n"),
             Catch::Contains("scene.yaml:5") && Catch::Contains("radius"));
}
