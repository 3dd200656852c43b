#include <catch2/catch.hpp>

#include <algorithm>
#include <iterator>
#include <set>

#include "kernels/embedded_programs.hpp"
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

TEST_CASE("every registered method has one name, a complete description and a program the build embedded") {
  std::set<std::string_view> names;
  REQUIRE_FALSE(solver::methods().empty());
  for (const solver::MethodDescription* m : solver::methods()) {
    INFO(m->name);
    CHECK(names.insert(m->name).second);
    CHECK_FALSE(m->summary.empty());
    CHECK(m->build != nullptr);
    CHECK(solver::find_method(m->name) == m);
    CHECK(kernels::program_source(m->program) != nullptr);  // kernels/<program>/<program>.cl, found by the build
    CHECK_FALSE(kernels::program_tasks(m->program).empty());
    for (const solver::MethodOption& o : m->options) {
      CHECK(o.default_value >= o.min);
      CHECK(o.default_value <= o.max);
    }
  }
}

TEST_CASE("every method's plan runs its program, with its own declared task kinds and the shared ones only") {
  // The kinds every method may use without declaring them (plan/task_kind.hpp).
  const plan::TaskKind shared[] = {plan::TaskKind::predict,  plan::TaskKind::jacobi,          plan::TaskKind::collision,
                                   plan::TaskKind::copy,     plan::TaskKind::update_velocity, plan::TaskKind::publish,
                                   plan::TaskKind::merge,    plan::TaskKind::energy,          plan::TaskKind::friction,
                                   plan::TaskKind::detection};
  const scene::SceneDesc s = cloth({"simulation.substeps=64"});  // a step every method takes, the explicit one too
  for (const solver::MethodDescription* m : solver::methods()) {
    INFO(m->name);
    const plan::SubstepPlan p = solver::build_plan(s, *m);
    CHECK(p.program == m->program);
    for (const sched::Task& t : p.graph.tasks()) {
      const plan::TaskKind k = plan::kind_of(t);
      INFO(t.name << ": " << k.name());
      const bool known = std::find(std::begin(shared), std::end(shared), k) != std::end(shared) ||
                         std::find(m->kinds.begin(), m->kinds.end(), k) != m->kinds.end();
      CHECK(known);
    }
    // Its iterations' kind carries its iteration scheme: async relaxes
    // Gauss-Seidel kinds, and only those of Gauss-Seidel methods.
    bool gauss_seidel_kind = false;
    for (const sched::Task& t : p.graph.tasks())
      gauss_seidel_kind = gauss_seidel_kind || plan::kind_of(t).traits().gauss_seidel;
    CHECK(gauss_seidel_kind == m->gauss_seidel);
  }
}

TEST_CASE("the methods known today have the capabilities the docs give them") {
  CHECK(solver::method("xpbd").gauss_seidel);
  CHECK(solver::method("vbd").gauss_seidel);
  CHECK_FALSE(solver::method("jpgd").gauss_seidel);
  CHECK_FALSE(solver::method("sosd").gauss_seidel);
  CHECK_FALSE(solver::method("explicit").gauss_seidel);
  CHECK_FALSE(solver::method("explicit").implicit);
  CHECK_FALSE(solver::method("explicit").colliders);
  CHECK(solver::method("vbd").descent);
  CHECK(solver::method("sosd").descent);
  CHECK(solver::method("jpgd").descent);
  CHECK_FALSE(solver::method("xpbd").descent);
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
    CHECK(std::string(e.what()) == "scene.yaml:9: unknown solver method 'fem'; available: " + solver::method_names());
    CHECK(solver::method_names().rfind("xpbd, vbd, sosd, jpgd, explicit", 0) == 0);  // registry order
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
  // The methods that do, from the registry.
  const std::string others = solver::method_names(
      [](const solver::MethodDescription& m) { return m.simulates(scene::SolidModel::neo_hookean); });
  CHECK(others.find("vbd, sosd, jpgd") != std::string::npos);
  CHECK(e.find("or use solver.method " + others) != std::string::npos);
  CHECK(error_of(s, "vbd").empty());
}
