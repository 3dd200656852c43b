#include <catch2/catch.hpp>

#include <string>

#include "scene/scene_loader.hpp"
#include "support/temp_dir.hpp"
#include "util/error.hpp"

using namespace atssim;

namespace {

// The message of the input error that parsing `yaml` raises ("" if none).
std::string error_of(const std::string& yaml, std::vector<std::string> overrides = {}) {
  try {
    scene::parse_scene(yaml, "scene.yaml", ".", overrides);
  } catch (const Error& e) {
    CHECK(e.exit_code() == 2);
    return e.what();
  }
  return "";
}

const std::string kGood =
    "simulation:\n"
    "  fps: 50\n"
    "  substeps: 10\n"
    "objects:\n"
    "  - name: sheet\n"
    "    grid: {size: [2, 1], resolution: [5, 4]}\n"
    "    material:\n"
    "      density: 0.3\n"
    "      stretch_stiffness: 100\n";

}  // namespace

TEST_CASE("a valid scene is read with its values and defaults") {
  const auto s = scene::parse_scene(kGood, "scene.yaml", ".");
  CHECK(s.simulation.frame_dt == Approx(0.02));
  CHECK(s.simulation.substeps == 10);
  CHECK(s.simulation.iterations == 8);
  REQUIRE(s.objects.size() == 1);
  CHECK(s.objects[0].name == "sheet");
  CHECK(s.objects[0].grid->resolution[0] == 5);
  CHECK(s.objects[0].material.has_stretch);
  CHECK(s.objects[0].material.stretch_compliance == Approx(0.01));
  CHECK_FALSE(s.objects[0].material.has_bending);
}

TEST_CASE("an unknown key names its line and suggests the right key") {
  const std::string yaml =
      "simulation:\n"
      "  fps: 60\n"
      "objects:\n"
      "  - grid: {size: [1, 1], resolution: [3, 3]}\n"
      "    material:\n"
      "      densty: 0.2\n";
  const std::string msg = error_of(yaml);
  CHECK(msg.find("scene.yaml:6:") == 0);
  CHECK(msg.find("unknown key 'densty'") != std::string::npos);
  CHECK(msg.find("did you mean 'density'?") != std::string::npos);
  CHECK(msg.find('\n') == std::string::npos);
}

TEST_CASE("a value of the wrong type names its line and the expected type") {
  const std::string yaml =
      "simulation:\n"
      "  substeps: lots\n"
      "objects:\n"
      "  - grid: {size: [1, 1], resolution: [3, 3]}\n";
  const std::string msg = error_of(yaml);
  CHECK(msg.find("scene.yaml:2:") == 0);
  CHECK(msg.find("whole number") != std::string::npos);
}

TEST_CASE("a negative density names its line and the valid range") {
  const std::string yaml =
      "objects:\n"
      "  - grid: {size: [1, 1], resolution: [3, 3]}\n"
      "    material:\n"
      "      density: -1\n";
  const std::string msg = error_of(yaml);
  CHECK(msg.find("scene.yaml:4:") == 0);
  CHECK(msg.find("density") != std::string::npos);
  CHECK(msg.find("> 0") != std::string::npos);
}

TEST_CASE("a missing mesh file names its line and the path") {
  test::TempDir dir;
  const std::string path = dir.write("scene.yaml",
                                     "objects:\n"
                                     "  - name: shirt\n"
                                     "    mesh: no_such_mesh.obj\n");
  try {
    scene::load_scene_file(path);
    FAIL("expected an error");
  } catch (const Error& e) {
    const std::string msg = e.what();
    CHECK(e.exit_code() == 2);
    CHECK(msg.find(path + ":3:") == 0);
    CHECK(msg.find("no_such_mesh.obj") != std::string::npos);
    CHECK(msg.find("does not exist") != std::string::npos);
  }
}

TEST_CASE("YAML syntax errors name their line") {
  const std::string msg = error_of("objects:\n  - grid: {size: [1, 1]\n    bad\n");
  CHECK(msg.find("scene.yaml:") == 0);
  CHECK(msg.find("YAML syntax error") != std::string::npos);
}

TEST_CASE("a ',' outside brackets is a syntax error naming its line, not a parser that never returns") {
  // yaml-cpp's LoadAll loops on these, its list of empty documents growing
  // until memory runs out (found by the fuzzer, docs/reliability.md).
  CHECK(error_of(",").find("scene.yaml:1: YAML syntax error: a ','") == 0);
  CHECK(error_of("- 1\n,\n").find("scene.yaml:2: YAML syntax error: a ','") == 0);
  CHECK(error_of("[1, 2],\n").find("scene.yaml:1: YAML syntax error: a ','") == 0);
}

TEST_CASE("a second YAML document is refused at its line") {
  CHECK(error_of(kGood + "---\nobjects: []\n").find("scene.yaml:11: a second YAML document") == 0);
  CHECK(error_of(kGood + "---\n,\n").find("a second YAML document") != std::string::npos);
}

TEST_CASE("set overrides (--set) replace any key before validation") {
  const std::vector<std::string> sets{"simulation.substeps=32", "objects.0.material.density=0.5",
                                      "objects.0.material.bend_stiffness=0.01"};
  const auto s = scene::parse_scene(kGood, "scene.yaml", ".", sets);
  CHECK(s.simulation.substeps == 32);
  CHECK(s.objects[0].material.density == Approx(0.5));
  CHECK(s.objects[0].material.has_bending);
  CHECK(s.resolved_yaml.find("substeps: 32") != std::string::npos);
}

TEST_CASE("the resolved scene reads back to the same description") {
  const auto s = scene::parse_scene(kGood, "scene.yaml", ".", std::vector<std::string>{"simulation.iterations=5"});
  const auto again = scene::parse_scene(s.resolved_yaml, "resolved.yaml", ".");
  CHECK(again.simulation.frame_dt == s.simulation.frame_dt);
  CHECK(again.simulation.iterations == 5);
  CHECK(again.simulation.frames == s.simulation.frames);  // the default, written out
  CHECK(again.objects[0].material.stretch_compliance == s.objects[0].material.stretch_compliance);
  CHECK(again.objects[0].grid->resolution == s.objects[0].grid->resolution);
  CHECK(again.output.path == s.output.path);
}

TEST_CASE("friction per material and a collider without friction survive the resolved YAML") {
  const std::string yaml = std::string(kGood) +
                           "colliders:\n  - {type: plane, thickness: 0.005}\n"
                           "  - {type: sphere, center: [0, 0, 0], radius: 0.1, friction: 0.3}\n";
  const auto s = scene::parse_scene(
      yaml, "scene.yaml", ".", std::vector<std::string>{"objects.0.material.friction={static: 0.5, kinetic: 0.25}"});
  REQUIRE(s.objects[0].material.has_friction);
  CHECK(s.objects[0].material.static_friction == 0.5);
  CHECK(s.objects[0].material.kinetic_friction == 0.25);
  REQUIRE(s.colliders.size() == 2);
  CHECK_FALSE(s.colliders[0].friction_set);  // the cloth's coefficients decide there
  CHECK(s.colliders[1].friction_set);
  const auto again = scene::parse_scene(s.resolved_yaml, "resolved.yaml", ".");
  CHECK(again.objects[0].material.has_friction);
  CHECK(again.objects[0].material.static_friction == 0.5);
  CHECK(again.objects[0].material.kinetic_friction == 0.25);
  CHECK_FALSE(again.colliders[0].friction_set);
  CHECK(again.colliders[1].kinetic_friction == 0.3);
}

TEST_CASE("an invalid override value is reported against its --set") {
  const std::string msg = error_of(kGood, {"simulation.substeps=-3"});
  CHECK(msg.find("--set simulation.substeps=-3") != std::string::npos);
  CHECK(msg.find("out of range") != std::string::npos);
  CHECK(error_of(kGood, {"simulation.substepz=3"}).find("did you mean 'substeps'?") != std::string::npos);
  CHECK(error_of(kGood, {"novalue"}).find("key=value") != std::string::npos);
}

TEST_CASE("stiffness zero means the term is not modelled") {
  const auto s =
      scene::parse_scene(kGood, "scene.yaml", ".", std::vector<std::string>{"objects.0.material.stretch_stiffness=0"});
  CHECK_FALSE(s.objects[0].material.has_stretch);
}

TEST_CASE("conflicting or missing settings are rejected", "[scene]") {
  CHECK(error_of("simulation: {fps: 60, dt: 0.01}\nobjects:\n  - grid: {}\n").find("both 'fps' and 'dt'") !=
        std::string::npos);
  CHECK(error_of("simulation: {fps: 60}\n").find("no 'objects'") != std::string::npos);
  CHECK(error_of("objects:\n  - name: a\n").find("exactly one of 'grid' or 'mesh'") != std::string::npos);
}

TEST_CASE("keys under solver that are no schedule keys are kept as written, with their lines") {
  const std::string yaml = std::string(kGood) + "solver:\n  method: sosd\n  stencil_step: 0.4\n";
  const auto s = scene::parse_scene(yaml, "scene.yaml", ".", std::vector<std::string>{"solver.momentum=0.6"});
  CHECK(s.solver.method == "sosd");
  REQUIRE(s.solver.method_options.size() == 2);
  CHECK(s.solver.method_options[0].key == "stencil_step");
  CHECK(s.solver.method_options[0].value == "0.4");
  CHECK(s.solver.method_options[0].where.rfind("scene.yaml:", 0) == 0);
  CHECK(s.solver.method_options[1].key == "momentum");
  CHECK(s.solver.method_options[1].where.find("--set solver.momentum=0.6") != std::string::npos);
  const auto again = scene::parse_scene(s.resolved_yaml, "resolved.yaml", ".");
  REQUIRE(again.solver.method_options.size() == 2);
  CHECK(again.solver.method_options[0].value == "0.4");
  CHECK(again.solver.method_options[1].value == "0.6");
  CHECK(error_of(kGood, {"solver.stencil_step=[1, 2]"}).find("should be text") != std::string::npos);
}
