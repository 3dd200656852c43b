// solver.tolerance / budget_ms / recheck / methods (lib/scene/accuracy_reader):
// their defaults, their ranges and their way through the resolved YAML; a
// bad value names its line (the bad-input suite runs them through the binary).
#include <catch2/catch.hpp>

#include <string>

#include "scene/scene_loader.hpp"
#include "util/error.hpp"

using namespace atssim;

namespace {

std::string scene_with(const std::string& solver) {
  return "simulation: {fps: 60, substeps: 2, iterations: 2, frames: 2}\n"
         "objects:\n"
         "  - {name: cloth, grid: {size: [1, 1], resolution: [8, 8]}, material: {density: 0.2, stretch_stiffness: "
         "1000}}\n"
         "solver:\n" +
         solver;
}

scene::SceneDesc parse(const std::string& solver) { return scene::parse_scene(scene_with(solver), "s.yaml", "."); }

}  // namespace

TEST_CASE("without a tolerance or a budget atssim chooses nothing, and re-checks every 30 frames when it does") {
  const auto plain = parse("  method: vbd\n");
  CHECK_FALSE(plain.solver.accuracy.active());
  CHECK(plain.solver.accuracy.recheck == 30);
  CHECK(plain.solver.accuracy.methods.empty());
  CHECK(plain.resolved_yaml.find("tolerance") == std::string::npos);
}

TEST_CASE("solver.tolerance, budget_ms, recheck and methods survive the resolved scene") {
  const auto s = parse("  tolerance: 1.0e-3\n  budget_ms: 12.5\n  recheck: 10\n  methods: [vbd, jpgd]\n");
  CHECK(s.solver.accuracy.tolerance == 1e-3);
  CHECK(s.solver.accuracy.budget_ms == 12.5);
  CHECK(s.solver.accuracy.recheck == 10);
  CHECK(s.solver.accuracy.methods == std::vector<std::string>{"vbd", "jpgd"});
  CHECK(s.solver.accuracy.methods_where == "s.yaml:8");
  const auto again = scene::parse_scene(s.resolved_yaml, "resolved.yaml", ".");
  CHECK(again.solver.accuracy.tolerance == 1e-3);
  CHECK(again.solver.accuracy.budget_ms == 12.5);
  CHECK(again.solver.accuracy.recheck == 10);
  CHECK(again.solver.accuracy.methods == s.solver.accuracy.methods);
  const auto set = scene::parse_scene(scene_with("  method: xpbd\n"), "s.yaml", ".",
                                      std::vector<std::string>{"solver.tolerance=0.01", "solver.methods=[xpbd]"});
  CHECK(set.solver.accuracy.tolerance == 0.01);
  CHECK(set.solver.accuracy.methods == std::vector<std::string>{"xpbd"});
}

TEST_CASE("a tolerance outside (0, 1), a budget of 0 or a method list without either names its line") {
  const auto message = [](const std::string& solver) -> std::string {
    try {
      parse(solver);
    } catch (const Error& e) {
      CHECK(e.exit_code() == 2);
      return e.what();
    }
    return "no error";
  };
  CHECK_THAT(message("  tolerance: 0\n"), Catch::StartsWith("s.yaml:5:") && Catch::Contains("0 < tolerance < 1"));
  CHECK_THAT(message("  tolerance: 1\n"), Catch::StartsWith("s.yaml:5:"));
  CHECK_THAT(message("  tolerance: -1e-3\n"), Catch::StartsWith("s.yaml:5:"));
  CHECK_THAT(message("  budget_ms: 0\n"), Catch::StartsWith("s.yaml:5:") && Catch::Contains("> 0"));
  CHECK_THAT(message("  tolerance: 0.1\n  recheck: -1\n"), Catch::StartsWith("s.yaml:6:"));
  CHECK_THAT(message("  methods: [vbd]\n"), Catch::StartsWith("s.yaml:5:") && Catch::Contains("solver.tolerance"));
  CHECK_THAT(message("  tolerance: 0.1\n  methods: []\n"), Catch::StartsWith("s.yaml:6:"));
}
