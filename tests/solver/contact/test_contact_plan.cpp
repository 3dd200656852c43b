#include <catch2/catch.hpp>

#include <fmt/format.h>

#include <string>
#include <vector>

#include "common/mesh_near.h"
#include "scene/scene_loader.hpp"
#include "solver/method_registry.hpp"
#include "support/obstacle_meshes.hpp"
#include "support/scenes.hpp"

using namespace atssim;

namespace {

int tasks_named(const plan::SubstepPlan& p, const std::string& part) {
  int n = 0;
  for (const sched::Task& t : p.graph.tasks()) n += t.name.find(part) != std::string::npos;
  return n;
}

}  // namespace

TEST_CASE("a scene without colliders gets no contact or friction task, in every method") {
  const scene::SceneDesc s = scene::parse_scene(test::hanging_cloth_yaml(6), "scene.yaml", ".");
  for (const solver::MethodDescription* m : solver::methods()) {
    if (!m->colliders) continue;  // refused with colliders (tested below)
    INFO(m->name);
    const plan::SubstepPlan p = solver::build_plan(s, *m);
    CHECK(p.tasks_of(plan::TaskKind::friction).empty());
    CHECK(tasks_named(p, "collision/colliders") == 0);
    CHECK(p.tasks_of(plan::TaskKind::update_velocity).size() == 1);  // a whole substep
  }
}

TEST_CASE("with colliders XPBD and JPGD project after every iteration, and every method has one friction task") {
  const scene::SceneDesc s = scene::parse_scene(
      test::hanging_cloth_yaml(6) + "colliders:\n  - {type: sphere, center: [0, -1, 0], radius: 0.5}\n", "scene.yaml",
      ".");
  const int iterations = s.simulation.iterations;
  for (const solver::MethodDescription* m : solver::methods()) {
    if (!m->colliders) continue;  // refused with colliders (tested below)
    INFO(m->name);
    const plan::SubstepPlan p = solver::build_plan(s, *m);
    // VBD and SOSD keep particles out through the contact energy alone.
    const bool projects = m->name == "xpbd" || m->name == "jpgd";
    CHECK(tasks_named(p, "collision/colliders") == (projects ? iterations : 0));
    REQUIRE(p.tasks_of(plan::TaskKind::friction).size() == 1);
    // Friction follows the last contact task and precedes the velocity update.
    const sched::TaskId friction = p.tasks_of(plan::TaskKind::friction).front();
    const sched::TaskId update = p.tasks_of(plan::TaskKind::update_velocity).front();
    std::vector<sched::TaskId> reach{friction};
    bool before_update = false;
    while (!reach.empty()) {
      const sched::TaskId t = reach.back();
      reach.pop_back();
      before_update = before_update || t == update;
      for (const sched::Edge& e : p.graph.successors(t)) reach.push_back(e.to);
    }
    CHECK(before_update);

    // Both range over every particle, so split and heft can cut them.
    for (const sched::TaskId t : p.tasks_of(plan::TaskKind::collision)) {
      REQUIRE(p.launches[t].size() == 1);
      CHECK(p.launches[t][0].range.count == p.particle_count);
    }
    CHECK(p.launches[friction][0].range.count == p.particle_count);
  }
}

TEST_CASE("a method without contact is refused for a scene with colliders, naming the collider's line") {
  const std::string yaml =
      test::hanging_cloth_yaml(6) + "colliders:\n  - {type: sphere, center: [0, -1, 0], radius: 0.5}\n";
  const scene::SceneDesc s = scene::parse_scene(yaml, "scene.yaml", ".");
  for (const solver::MethodDescription* m : solver::methods()) {
    if (m->colliders) continue;
    INFO(m->name);
    const int line = s.colliders.front().source_line;
    CHECK_THROWS_WITH(solver::build_plan(s, *m), Catch::Contains(fmt::format("scene.yaml:{}", line)) &&
                                                     Catch::Contains("no contact with colliders"));
  }
}

TEST_CASE("with a mesh collider every method keeps its near lists once a substep, after predict, per particle") {
  scene::SceneDesc s = scene::parse_scene(
      test::hanging_cloth_yaml(6) + "colliders:\n  - {type: sphere, center: [0, -1, 0], radius: 0.5}\n", "scene.yaml",
      ".");
  for (const solver::MethodDescription* m : solver::methods()) {
    if (!m->colliders) continue;
    INFO(m->name);
    CHECK(tasks_named(solver::build_plan(s, *m), "collision/near_lists") == 0);  // a sphere needs none
  }
  const test::SimpleMesh sheet = test::sheet(1.0, 4);
  s.colliders.front().shape = scene::ColliderShape::mesh;
  s.colliders.front().mesh_vertices = sheet.vertices;
  s.colliders.front().mesh_triangles = sheet.triangles;
  for (const solver::MethodDescription* m : solver::methods()) {
    if (!m->colliders) continue;
    INFO(m->name);
    const plan::SubstepPlan p = solver::build_plan(s, *m);
    REQUIRE(tasks_named(p, "collision/near_lists") == 1);
    sched::TaskId near = -1;
    for (const sched::TaskId t : p.tasks_of(plan::TaskKind::collision)) {
      if (p.graph.task(t).name.find("near_lists") != std::string::npos) near = t;
    }
    // right after predict, over every particle, writing only each particle's own list
    const sched::TaskId predict = p.tasks_of(plan::TaskKind::predict).front();
    bool follows = false;
    for (const sched::Edge& e : p.graph.successors(predict)) follows = follows || e.to == near;
    CHECK(follows);
    REQUIRE(p.launches[near].size() == 1);
    CHECK(p.launches[near][0].range.count == p.particle_count);
    REQUIRE(p.launches[near][0].writes.size() == 1);
    CHECK(p.launches[near][0].writes[0].element_bytes == sizeof(ats_mesh_near));
  }
}
