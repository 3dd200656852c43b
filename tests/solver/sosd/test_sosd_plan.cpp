#include <catch2/catch.hpp>

#include <set>

#include "model/cloth_builder.hpp"
#include "scene/scene_loader.hpp"
#include "solver/sosd/sosd_plan.hpp"
#include "support/scenes.hpp"

using namespace atssim;
using namespace atssim::solver;

TEST_CASE("SOSD blocks are the element colors, and no two stencils of a block share a vertex") {
  const auto m = model::build_model(scene::parse_scene(test::hanging_cloth_yaml(10, 1e4, 1e-3), "s.yaml", "."));
  const auto layout = make_sim_layout(m);
  const auto blocks = sosd::stencil_blocks(layout);
  REQUIRE(blocks.size() == layout.stretch_blocks.size() - 1 + layout.bend_blocks.size() - 1);
  std::size_t stretch = 0, bend = 0;
  for (const auto& b : blocks) {
    std::set<int> seen;
    for (int e = b.first; e < b.end; ++e) {
      std::vector<int> v;
      if (b.kind == 0) {
        v = {layout.stretch[e].a, layout.stretch[e].b};
        ++stretch;
      } else {
        REQUIRE(b.kind == 1);
        v.assign(layout.bend[e].v, layout.bend[e].v + 4);
        ++bend;
      }
      for (int i : v) {
        if (layout.x[i].w == 0.0f) continue;  // pinned particles are never moved
        CHECK(seen.insert(i).second);
      }
    }
  }
  CHECK(stretch == layout.stretch.size());  // every element is one stencil
  CHECK(bend == layout.bend.size());
}

TEST_CASE("an SOSD iteration is vertex systems, the main block beside the Jacobi rest, then one combine") {
  const int iterations = 3;
  const auto m = model::build_model(scene::parse_scene(test::hanging_cloth_yaml(10, 1e4, 1e-3), "s.yaml", "."));
  const auto layout = make_sim_layout(m);
  const auto plan = sosd::make_sosd_plan(layout, 1.0 / 240.0, iterations);
  const auto blocks = sosd::stencil_blocks(layout);
  const auto systems = plan.tasks_of(solver::sosd::kSystems);
  const auto combines = plan.tasks_of(solver::sosd::kCombine);
  REQUIRE(systems.size() == std::size_t(iterations));
  REQUIRE(combines.size() == std::size_t(iterations));
  CHECK(plan.tasks_of(solver::sosd::kMainBlock).size() == std::size_t(iterations));
  const int counts[2] = {static_cast<int>(layout.stretch.size()), static_cast<int>(layout.bend.size())};
  for (int it = 0; it < iterations; ++it) {
    // The stencil tasks of one iteration follow its systems task only and all
    // precede its combine: they may run side by side on any device. Together
    // they solve every element exactly once.
    std::vector<int> solved[2] = {std::vector<int>(counts[0], 0), std::vector<int>(counts[1], 0)};
    for (sched::TaskId t = 0; t < plan.graph.size(); ++t) {
      const auto& task = plan.graph.task(t);
      const plan::TaskKind k = plan::kind_of(task);
      if (task.iteration != it || (k != solver::sosd::kStencils && k != solver::sosd::kMainBlock)) continue;
      REQUIRE(plan.graph.predecessors(t).size() == 1);
      CHECK(plan.graph.predecessors(t).front().from == systems[it]);
      REQUIRE(plan.graph.successors(t).size() == 1);
      CHECK(plan.graph.successors(t).front().to == combines[it]);
      for (const auto& l : plan.launches[t]) {
        const int kind = l.function == "sosd_stretch" ? 0 : 1;
        REQUIRE((l.function == "sosd_stretch" || l.function == "sosd_bend"));
        const int first = l.range.first, count = l.range.count;
        for (int e = first; e < first + count; ++e) ++solved[kind][e];
        if (k == solver::sosd::kMainBlock) {  // the iteration's main block, rotating through the blocks
          const auto& b = blocks[it % blocks.size()];
          CHECK(b.kind == kind);
          CHECK(first == b.first);
          CHECK(first + count == b.end);
        }
      }
    }
    for (const auto& s : solved) {
      for (int c : s) CHECK(c == 1);
    }
  }
  // Every task but the Jacobi rest of the main block's kind has one launch: split may cut it.
  for (sched::TaskId t = 0; t < plan.graph.size(); ++t) {
    if (plan::kind_of(plan.graph.task(t)) != solver::sosd::kStencils) CHECK(plan.launches[t].size() == 1);
  }
}
