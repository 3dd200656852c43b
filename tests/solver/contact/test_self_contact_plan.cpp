#include <catch2/catch.hpp>

#include <algorithm>
#include <string>
#include <vector>

#include "model/cloth_builder.hpp"
#include "scene/scene_loader.hpp"
#include "solver/layout/sim_layout.hpp"
#include "solver/method_registry.hpp"
#include "support/scenes.hpp"
#include "util/error.hpp"

using namespace atssim;

namespace {

const std::string kContact = "contact: {self: true, thickness: 0.01}\n";

int tasks_named(const plan::SubstepPlan& p, const std::string& part) {
  int n = 0;
  for (const sched::Task& t : p.graph.tasks()) n += t.name.find(part) != std::string::npos;
  return n;
}

}  // namespace

TEST_CASE("a scene without contact gets no detection or surface contact task, in every method", "[self]") {
  const scene::SceneDesc s = scene::parse_scene(test::hanging_cloth_yaml(6), "scene.yaml", ".");
  CHECK_FALSE(s.contact.enabled);
  for (const solver::MethodDescription* m : solver::methods()) {
    if (!m->colliders) continue;  // explicit: refuses contact (tested below), and this substep is unstable for it
    INFO(m->name);
    const plan::SubstepPlan p = solver::build_plan(s, *m);
    CHECK(p.tasks_of(plan::TaskKind::detection).empty());
    CHECK(tasks_named(p, "contact/") == 0);
    CHECK(tasks_named(p, "collision/surfaces") == 0);
    CHECK(tasks_named(p, "collision/bound") == 0);
  }
}

TEST_CASE("with contact every method detects once per substep before its iterations", "[self]") {
  const scene::SceneDesc s = scene::parse_scene(test::hanging_cloth_yaml(12) + kContact, "scene.yaml", ".");
  REQUIRE(s.contact.enabled);
  const int iterations = s.simulation.iterations;
  for (const solver::MethodDescription* m : solver::methods()) {
    if (!m->colliders) continue;  // refused (tested below)
    INFO(m->name);
    const plan::SubstepPlan p = solver::build_plan(s, *m);
    // one walk per leaf for its triangle's, vertices' and edges' pairs
    CHECK(tasks_named(p, "detect/pairs") == 1);
    CHECK(tasks_named(p, "detect/bound") == 1);
    CHECK(tasks_named(p, "contact/first_guess") == 1);
    for (sched::TaskId t : p.tasks_of(plan::TaskKind::detection)) CHECK(p.graph.task(t).iteration < 0);
    // XPBD bounds its constraint step and projects every iteration; JPGD and
    // SOSD bound every iterate; VBD bounds inside its solve and keeps the
    // iteration's start for a contact partner of the vertex's own colour.
    CHECK(tasks_named(p, "collision/surfaces") == (m->name == "xpbd" ? iterations : 0));
    // per iteration the three kinds of near list (each vertex's displacement
    // since x_t is measured by the clamp, collision/bound)
    CHECK(tasks_named(p, "collision/surface_pairs/") == (m->name == "xpbd" ? 3 * iterations : 0));
    CHECK(tasks_named(p, "collision/bound") == (m->name == "vbd" ? 0 : iterations));
    CHECK(tasks_named(p, "contact/iteration_start") == (m->name == "vbd" ? 1 : 0));
    CHECK(tasks_named(p, "collision/iteration_end") == (m->name == "vbd" ? iterations - 1 : 0));
  }
}

TEST_CASE(
    "the surface layout: every triangle a leaf, every vertex and edge owned by one leaf, each vertex joined to the "
    "other ends of its edges",
    "[self]") {
  const scene::SceneDesc s = scene::parse_scene(test::hanging_cloth_yaml(9) + kContact, "scene.yaml", ".");
  const solver::SelfContactLayout l = solver::make_sim_layout(model::build_model(s)).self_contact;
  REQUIRE(l.enabled);
  const int n = 81, tris = 2 * 8 * 8, edges = 8 * 9 * 2 + 8 * 8;
  CHECK(int(l.tris.size()) == tris);
  CHECK(int(l.edges.size()) == edges);
  std::vector<int> vertex_owned(n, 0), edge_owned(edges, 0);
  for (const auto& leaf : l.leaves) {
    for (int k = 0; k < 3; ++k) {
      if (leaf[k] >= 0) ++vertex_owned[leaf[k]];
      if (leaf[4 + k] >= 0) ++edge_owned[leaf[4 + k]];
    }
  }
  for (int v : vertex_owned) CHECK(v == 1);
  for (int e : edge_owned) CHECK(e == 1);
  // The joined vertices (incidence's third section, sc_joined): two corners
  // of one triangle share one of its edges, so each vertex's are the other
  // ends of its edges, every edge counted at both ends.
  const auto joined = [&](int v) {
    const int* at = l.incidence.data() + l.incidence[2 * (n + 1) + v];
    return std::vector<int>(at, l.incidence.data() + l.incidence[2 * (n + 1) + v + 1]);
  };
  int listed = 0;
  for (int v = 0; v < n; ++v) listed += int(joined(v).size());
  CHECK(listed == 2 * edges);
  for (const auto& e : l.edges) {
    const std::vector<int> a = joined(e[0]), b = joined(e[1]);
    CHECK(std::count(a.begin(), a.end(), e[1]) == 1);
    CHECK(std::count(b.begin(), b.end(), e[0]) == 1);
  }
  // Levels halve up to one root.
  CHECK(l.levels.front() == 0);
  CHECK(l.levels[1] == tris);
  CHECK(l.levels.back() - l.levels[l.levels.size() - 2] == 1);
}

TEST_CASE("a contact thickness too large for the mesh names the contact line", "[self]") {
  // 6 x 6 vertices on 1 m: edges of 0.2 m, so a thickness of 0.15 is refused.
  const scene::SceneDesc s =
      scene::parse_scene(test::hanging_cloth_yaml(6) + "contact: {self: true, thickness: 0.15}\n", "scene.yaml", ".");
  CHECK_THROWS_WITH(model::build_model(s), Catch::Contains("scene.yaml:") && Catch::Contains("shortest surface edge"));
}

TEST_CASE("a query radius below the thickness is refused at its line", "[self]") {
  CHECK_THROWS_WITH(
      scene::parse_scene(test::hanging_cloth_yaml(6) + "contact: {self: true, thickness: 0.01, query_radius: 0.005}\n",
                         "scene.yaml", "."),
      Catch::Contains("scene.yaml:") && Catch::Contains("query_radius"));
}

TEST_CASE("a method without contact refuses a scene with contact between objects, at the contact line", "[self]") {
  const scene::SceneDesc s = scene::parse_scene(test::hanging_cloth_yaml(6) + kContact, "scene.yaml", ".");
  for (const solver::MethodDescription* m : solver::methods()) {
    if (m->colliders) continue;
    INFO(m->name);
    CHECK_THROWS_WITH(solver::build_plan(s, *m), Catch::Contains("scene.yaml:") && Catch::Contains("between objects"));
  }
}
