#include <catch2/catch.hpp>

#include "model/cloth_builder.hpp"
#include "scene/scene_loader.hpp"
#include "solver/xpbd/xpbd_plan.hpp"
#include "support/scenes.hpp"

using namespace atssim;
using namespace atssim::solver;
using namespace atssim::solver::xpbd;

namespace {

plan::SubstepPlan plan_for(double stretch, double bend, int iterations) {
  const auto m =
      model::build_model(scene::parse_scene(test::hanging_cloth_yaml(10, stretch, bend, iterations), "s.yaml", "."));
  return make_xpbd_plan(make_sim_layout(m), {1.0 / 240.0, iterations});
}

}  // namespace

TEST_CASE("a scene with bending stiffness 0 has no bending task") {
  const auto plan = plan_for(1e4, 0.0, 4);
  CHECK(plan.tasks_of(solver::xpbd::kBend).empty());
  CHECK_FALSE(plan.tasks_of(solver::xpbd::kStretch).empty());
  for (const auto& b : plan.buffers) CHECK(b.name.find("bend") == std::string::npos);
}

TEST_CASE("the XPBD substep graph is predict, iterations of color blocks, update velocity") {
  const int iterations = 3;
  const auto m = model::build_model(scene::parse_scene(test::hanging_cloth_yaml(10, 1e4, 1e-3), "s.yaml", "."));
  const auto layout = make_sim_layout(m);
  const auto plan = make_xpbd_plan(layout, {1.0 / 240.0, iterations});
  const int stretch_blocks = static_cast<int>(layout.stretch_blocks.size()) - 1;
  const int bend_blocks = static_cast<int>(layout.bend_blocks.size()) - 1;
  CHECK(plan.graph.size() == std::size_t(2 + iterations * (stretch_blocks + bend_blocks)));
  CHECK(plan.tasks_of(solver::xpbd::kStretch).size() == std::size_t(iterations * stretch_blocks));
  CHECK(plan.tasks_of(solver::xpbd::kBend).size() == std::size_t(iterations * bend_blocks));
  // A Gauss-Seidel chain: the topological order is unique and starts/ends right.
  const auto order = plan.graph.topological_order();
  CHECK(plan::kind_of(plan.graph.task(order.front())) == plan::TaskKind::predict);
  CHECK(plan::kind_of(plan.graph.task(order.back())) == plan::TaskKind::update_velocity);
  CHECK(plan.graph.edge_count() == plan.graph.size() - 1);
  for (std::size_t i = 1; i < order.size(); ++i) {
    REQUIRE(plan.graph.predecessors(order[i]).size() == 1);
    CHECK(plan.graph.predecessors(order[i])[0].from == order[i - 1]);
  }
  CHECK(plan.launches.size() == plan.graph.size());
}
