// The paper's five scenes at the paper's size (scenes/paper/NAME.yaml):
// each loads and validates, builds its model and its substep's task graph
// (without a device: a frame of them runs in test_paper_size_runs, label
// paper_size, minutes), and has the vertex, cloth-triangle and tetrahedron
// counts that docs/scenes.md states; so does each small variant.
#include <catch2/catch.hpp>

#include <string>

#include "app/simulation.hpp"
#include "model/cloth_builder.hpp"
#include "plan/substep_plan.hpp"
#include "support/paper_scenes.hpp"
#include "support/temp_dir.hpp"

using namespace atssim;

namespace {

struct Counted {
  long long vertices = 0, triangles = 0, tetrahedra = 0;
};

// Vertices of the model, triangles of its cloths (a solid's are its
// surface, which the table does not count), tetrahedra.
Counted count(const model::Model& m) {
  Counted c;
  c.vertices = static_cast<long long>(m.particles.size());
  for (const model::ObjectRange& o : m.objects) {
    if (o.tetrahedra.empty()) c.triangles += static_cast<long long>(o.triangles.size());
  }
  c.tetrahedra = static_cast<long long>(m.tets.size());
  return c;
}

void check_counts(const std::string& name, bool small, const model::Model& m) {
  const test::StatedSize stated = test::stated_size(name, small);
  const Counted c = count(m);
  INFO(name << (small ? " (small)" : " (paper size)") << ": " << c.vertices << " v, " << c.triangles << " cloth tris, "
            << c.tetrahedra << " tets; docs/scenes.md: " << stated.vertices << " v, " << stated.triangles << " tris, "
            << stated.tetrahedra << " tets");
  REQUIRE(stated.vertices > 0);  // the scene has its row in the table
  CHECK(c.vertices == stated.vertices);
  CHECK(c.triangles == stated.triangles);
  CHECK(c.tetrahedra == stated.tetrahedra);
}

}  // namespace

TEST_CASE("each paper-size scene loads, builds its model and task graph, and has the sizes docs/scenes.md states",
          "[paper]") {
  test::TempDir dir;
  const auto paper = test::paper_scene_copy(dir);
  const auto names = test::paper_size_scenes();
  REQUIRE(names.size() == 5);  // dress, funnel, jersey, letters, pillows (tests/check_doc_counts.py counts them)
  for (const std::string& name : names) {
    INFO(name);
    const scene::SceneDesc scene = app::load_scene((paper / (name + ".yaml")).string(), {});
    CHECK(scene.solver.method == "xpbd");  // the paper's Table-1 method, docs/scenes.md
    check_counts(name, false, model::build_model(scene));
    const plan::SubstepPlan plan = app::substep_plan_for(scene);
    CHECK(plan.graph.size() > 0);
  }
}

TEST_CASE("each small paper scene has the sizes docs/scenes.md states, at most 3.1 K vertices", "[paper][fast]") {
  for (const std::string& name : test::paper_size_scenes()) {
    const std::string path = std::string(ATSSIM_SOURCE_DIR) + "/scenes/paper/" + name + "_small.yaml";
    const model::Model m = model::build_model(app::load_scene(path, {}));
    check_counts(name, true, m);
    CHECK(m.particles.size() <= 3100);
  }
}
