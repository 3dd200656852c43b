#include <catch2/catch.hpp>

#include <string>

#include "scene/scene_loader.hpp"
#include "util/error.hpp"

using namespace atssim;

namespace {

const std::string kCloth =
    "objects:\n"
    "  - grid: {size: [1, 1], resolution: [4, 4]}\n"
    "    material: {stretch_stiffness: 100}\n";

// The message of the input error that parsing the cloth with `colliders`
// raises ("" if none); checks the exit code is 2.
std::string error_of(const std::string& colliders) {
  try {
    scene::parse_scene(kCloth + "colliders:\n" + colliders, "scene.yaml", ".");
  } catch (const Error& e) {
    CHECK(e.exit_code() == 2);
    return e.what();
  }
  return "";
}

}  // namespace

TEST_CASE("the four collider shapes are read with their values and defaults") {
  const auto s = scene::parse_scene(kCloth +
                                        "colliders:\n"
                                        "  - {type: plane, point: [0, 1, 0], normal: [0, 2, 0], friction: 0.4}\n"
                                        "  - {type: sphere, center: [0, 0.5, 0], radius: 0.3, thickness: 0.01}\n"
                                        "  - {type: capsule, a: [0, 0, 0], b: [1, 0, 0], radius: 0.1}\n"
                                        "  - type: box\n"
                                        "    center: [1, 2, 3]\n"
                                        "    size: [1, 0.5, 2]\n"
                                        "    rotate: [0, 45, 0]\n"
                                        "    friction: {static: 0.6, kinetic: 0.3}\n",
                                    "scene.yaml", ".");
  REQUIRE(s.colliders.size() == 4);
  CHECK(s.colliders[0].shape == scene::ColliderShape::plane);
  CHECK(s.colliders[0].static_friction == 0.4);
  CHECK(s.colliders[0].kinetic_friction == 0.4);
  CHECK(s.colliders[0].thickness == 0.005);  // the default
  CHECK(s.colliders[1].shape == scene::ColliderShape::sphere);
  CHECK(s.colliders[1].radius == 0.3);
  CHECK(s.colliders[1].thickness == 0.01);
  CHECK(s.colliders[2].end[0] == 1.0);
  CHECK(s.colliders[3].size[2] == 2.0);
  CHECK(s.colliders[3].rotate_deg[1] == 45.0);
  CHECK(s.colliders[3].static_friction == 0.6);
  CHECK(s.colliders[3].kinetic_friction == 0.3);
  // The resolved YAML reads back to the same colliders.
  const auto again = scene::parse_scene(s.resolved_yaml, "resolved.yaml", ".");
  REQUIRE(again.colliders.size() == 4);
  CHECK(again.colliders[3].kinetic_friction == 0.3);
  CHECK(again.colliders[1].radius == 0.3);
}

TEST_CASE("bad colliders name the line and the fix, exit code 2") {
  // The first collider entry starts on line 5 of the scene (the cloth takes 3, 'colliders:' the 4th).
  CHECK_THAT(error_of("  - {type: sphere, center: [0, 0, 0], radius: -0.3}\n"),
             Catch::Contains("scene.yaml:5") && Catch::Contains("radius") && Catch::Contains("positive"));
  CHECK_THAT(error_of("  - {type: capsule, a: [0, 0, 0], b: [1, 0, 0], radius: 0}\n"), Catch::Contains("radius"));
  CHECK_THAT(error_of("  - {type: plane, thickness: -0.01}\n"),
             Catch::Contains("scene.yaml:5") && Catch::Contains("thickness"));
  CHECK_THAT(error_of("  - {type: plane, friction: -0.1}\n"),
             Catch::Contains("scene.yaml:5") && Catch::Contains("friction coefficient"));
  CHECK_THAT(error_of("  - {type: plane, friction: {static: 0.5, kinetic: -1}}\n"),
             Catch::Contains("kinetic") && Catch::Contains("friction coefficient"));
  CHECK_THAT(error_of("  - {type: box, center: [0, 0, 0], size: [1, -1, 1]}\n"), Catch::Contains("size"));
  CHECK_THAT(error_of("  - {type: plane, normal: [0, 0, 0]}\n"), Catch::Contains("normal is zero"));
  CHECK_THAT(error_of("  - {type: sphre, center: [0, 0, 0], radius: 1}\n"), Catch::Contains("did you mean 'sphere'"));
  CHECK_THAT(error_of("  - {type: sphere, radius: 1}\n"), Catch::Contains("needs 'center'"));
  CHECK_THAT(error_of("  - {type: sphere, center: [0, 0, 0], radius: 1, size: [1, 1, 1]}\n"),
             Catch::Contains("unknown key 'size'"));
}
