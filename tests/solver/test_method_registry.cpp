#include <catch2/catch.hpp>

#include <set>

#include "scene/scene_loader.hpp"
#include "solver/method_registry.hpp"
#include "support/scenes.hpp"
#include "util/error.hpp"

using namespace atssim;

namespace {

scene::SceneDesc cloth(std::vector<std::string> sets = {}) {
  return scene::parse_scene(test::hanging_cloth_yaml(6), "scene.yaml", ".", sets);
}

std::string error_of(const scene::SceneDesc& s, std::string_view method) {
  try {
    solver::method_settings(s, solver::method(method));
  } catch (const Error& e) {
    CHECK(e.exit_code() == 2);
    return e.what();
  }
  return "";
}

}  // namespace

TEST_CASE("the registry names five methods once each, and every description is complete") {
  std::set<std::string_view> names;
  for (const solver::MethodDescription* m : solver::methods()) {
    INFO(m->name);
    CHECK(names.insert(m->name).second);
    CHECK_FALSE(m->summary.empty());
    CHECK(m->build != nullptr);
    CHECK(solver::find_method(m->name) == m);
    for (const solver::MethodOption& o : m->options) {
      CHECK(o.default_value >= o.min);
      CHECK(o.default_value <= o.max);
    }
  }
  CHECK(names == std::set<std::string_view>{"xpbd", "vbd", "sosd", "jpgd", "explicit"});
  CHECK(solver::method("xpbd").gauss_seidel);
  CHECK(solver::method("vbd").gauss_seidel);
  CHECK_FALSE(solver::method("jpgd").gauss_seidel);
  CHECK_FALSE(solver::method("sosd").gauss_seidel);
  CHECK_FALSE(solver::method("explicit").gauss_seidel);
}

TEST_CASE("a named option takes one of its names, read as its index, another name is refused with a guess") {
  const auto s = solver::method_settings(cloth({"solver.integrator=rk4"}), solver::method("explicit"));
  CHECK(s.option("integrator") == 2.0);
  CHECK(s.option("allow_unstable") == 0.0);  // default: false
  CHECK(solver::method("explicit").options[0].default_text() == "semi_euler");
  const std::string e = error_of(cloth({"solver.integrator=rk5"}), "explicit");
  CHECK(e.find("solver.integrator is 'rk5'; use semi_euler, midpoint or rk4") != std::string::npos);
  CHECK(e.find("did you mean 'rk4'?") != std::string::npos);
}

TEST_CASE("an unknown method is an input error naming the line and the methods") {
  try {
    solver::method("fem", "scene.yaml:9");
    FAIL("no error");
  } catch (const Error& e) {
    CHECK(e.exit_code() == 2);
    CHECK(std::string(e.what()).find("scene.yaml:9: unknown solver method 'fem'; available: xpbd, vbd, sosd, jpgd") !=
          std::string::npos);
  }
}

TEST_CASE("method options are read with defaults, range-checked and named by their line") {
  const auto given = cloth({"solver.stencil_step=0.4", "solver.jacobi_step=0.25", "solver.momentum=0.6"});
  const auto sosd = solver::method_settings(given, solver::method("sosd"));
  CHECK(sosd.option("stencil_step") == 0.4);
  const auto jpgd = solver::method_settings(given, solver::method("jpgd"));
  CHECK(jpgd.option("jacobi_step") == 0.25);
  CHECK(jpgd.option("momentum") == 0.6);
  CHECK(jpgd.option("chebyshev_rho") == 0.9);  // the default
  CHECK(solver::method_settings(cloth(), solver::method("sosd")).option("stencil_step") == 0.7);
  CHECK_THROWS_AS(sosd.option("momentum"), Error);  // not an option of sosd

  CHECK(error_of(cloth({"solver.momentum=1"}), "jpgd").find("momentum") != std::string::npos);
  for (const char* bad :
       {"solver.stencil_step=0", "solver.stencil_step=1.5", "solver.jacobi_step=-1", "solver.jacobi_step=abc"}) {
    INFO(bad);
    const std::string method = std::string(bad).find("stencil") != std::string::npos ? "sosd" : "jpgd";
    const std::string e = error_of(cloth({bad}), method);
    CHECK(e.find("step length") != std::string::npos);
    CHECK(e.find("--set " + std::string(bad)) != std::string::npos);
  }
  // An option of another method is accepted (it applies when that method runs);
  // a key no method knows is a typo.
  CHECK(error_of(cloth({"solver.stencil_step=0.5"}), "xpbd").empty());
  CHECK(error_of(cloth({"solver.stencil_stp=0.5"}), "sosd").find("did you mean 'stencil_step'?") != std::string::npos);
}

TEST_CASE("a solid model the method does not simulate is refused naming the line that chose it") {
  const std::string yaml =
      "objects:\n"
      "  - name: box\n"
      "    type: solid\n"
      "    box: {size: [0.2, 0.2, 0.2], resolution: [1, 1, 1]}\n"
      "    material:\n"
      "      model: neo_hookean\n";
  const auto s = scene::parse_scene(yaml, "solid.yaml", ".");
  const std::string e = error_of(s, "xpbd");
  CHECK(e.find("solid.yaml:6") != std::string::npos);
  CHECK(e.find("vbd, sosd, jpgd") != std::string::npos);
  CHECK(error_of(s, "vbd").empty());
}
