#include <catch2/catch.hpp>

#include <string>

#include "scene/scene_loader.hpp"
#include "scene/scene_yaml.hpp"
#include "util/error.hpp"

using namespace atssim;

namespace {

const std::string kCloth =
    "objects:\n"
    "  - grid: {size: [1, 1], resolution: [4, 4]}\n"
    "    material: {stretch_stiffness: 100}\n"
    "colliders:\n";  // line 4; the first collider is on line 5

// The message of the input error that parsing the cloth with `colliders`
// raises ("" if none); checks the exit code is 2.
std::string error_of(const std::string& colliders) {
  try {
    scene::parse_scene(kCloth + colliders, "scene.yaml", ".");
  } catch (const Error& e) {
    CHECK(e.exit_code() == 2);
    return e.what();
  }
  return "";
}

}  // namespace

TEST_CASE("a collider's velocity and angular velocity are read, without them it is still") {
  const auto s = scene::parse_scene(kCloth +
                                        "  - {type: sphere, center: [0, 0, 0], radius: 0.1, velocity: [1, 2, 3],\n"
                                        "     angular_velocity: [0, 0.5, 0]}\n"
                                        "  - {type: sphere, center: [0, 0, 0], radius: 0.1, velocity: [0, 0, 1]}\n"
                                        "  - {type: plane}\n",
                                    "scene.yaml", ".");
  REQUIRE(s.colliders.size() == 3);
  CHECK(s.colliders[0].motion.kind == scene::MotionKind::velocity);
  CHECK(s.colliders[0].motion.velocity[2] == 3.0);
  CHECK(s.colliders[0].motion.angular_velocity[1] == 0.5);
  CHECK(s.colliders[1].motion.kind == scene::MotionKind::velocity);
  CHECK(s.colliders[1].motion.angular_velocity[1] == 0.0);
  CHECK(s.colliders[2].motion.kind == scene::MotionKind::still);
}

TEST_CASE("keyframes are read in order, rotation optional, and survive the resolved YAML") {
  const auto s = scene::parse_scene(kCloth +
                                        "  - type: box\n"
                                        "    center: [0, 0, 0]\n"
                                        "    size: [1, 1, 1]\n"
                                        "    keyframes:\n"
                                        "      - {time: 0, position: [0, 0, 0]}\n"
                                        "      - {time: 1.5, position: [1, 0, 0], rotation: [0, 90, 0]}\n",
                                    "scene.yaml", ".");
  const auto& m = s.colliders.at(0).motion;
  REQUIRE(m.kind == scene::MotionKind::keyframes);
  REQUIRE(m.keyframes.size() == 2);
  CHECK(m.keyframes[1].time == 1.5);
  CHECK(m.keyframes[1].position[0] == 1.0);
  CHECK(m.keyframes[1].rotation_deg[1] == 90.0);
  CHECK(m.keyframes[0].rotation_deg[1] == 0.0);
  const auto again = scene::parse_scene(scene::to_resolved_yaml(s), "resolved.yaml", ".");
  const auto& n = again.colliders.at(0).motion;
  REQUIRE(n.keyframes.size() == 2);
  CHECK(n.keyframes[1].rotation_deg[1] == 90.0);
  CHECK(n.keyframes[1].time == 1.5);
}

TEST_CASE("bad motion keys stop with the line and exit code 2") {
  CHECK_THAT(error_of("  - type: sphere\n"
                      "    center: [0, 0, 0]\n"
                      "    radius: 0.1\n"
                      "    keyframes:\n"
                      "      - {time: 1, position: [0, 0, 0]}\n"
                      "      - {time: 1, position: [1, 0, 0]}\n"),
             Catch::Contains("scene.yaml:10") && Catch::Contains("increasing time"));
  CHECK_THAT(error_of("  - type: sphere\n"
                      "    center: [0, 0, 0]\n"
                      "    radius: 0.1\n"
                      "    velocity: [1, 0, 0]\n"
                      "    keyframes: [{time: 0, position: [0, 0, 0]}]\n"),
             Catch::Contains("scene.yaml:9") && Catch::Contains("both keyframes and a velocity"));
  CHECK_THAT(error_of("  - {type: sphere, center: [0, 0, 0], radius: 0.1, velocity: [1, 0]}\n"),
             Catch::Contains("scene.yaml:5") && Catch::Contains("list of 3 numbers"));
  CHECK_THAT(error_of("  - {type: sphere, center: [0, 0, 0], radius: 0.1, angular_velocity: [1, 0, 0, 4]}\n"),
             Catch::Contains("scene.yaml:5") && Catch::Contains("list of 3 numbers"));
  CHECK_THAT(error_of("  - {type: sphere, center: [0, 0, 0], radius: 0.1, keyframes: [{time: 0}]}\n"),
             Catch::Contains("scene.yaml:5") && Catch::Contains("'position'"));
  CHECK_THAT(error_of("  - {type: sphere, center: [0, 0, 0], radius: 0.1, keyframes: []}\n"),
             Catch::Contains("scene.yaml:5") && Catch::Contains("empty"));
  CHECK_THAT(
      error_of("  - {type: sphere, center: [0, 0, 0], radius: 0.1, keyframes: [{time: -1, position: [0, 0, 0]}]}\n"),
      Catch::Contains("scene.yaml:5"));
}
