#include <catch2/catch.hpp>

#include "model/cloth_builder.hpp"
#include "plan/async_graph.hpp"
#include "plan/substep_plan.hpp"
#include "scene/scene_loader.hpp"
#include "sched/gauss_seidel_rank.hpp"
#include "sched/sync_map.hpp"
#include "solver/xpbd/xpbd_plan.hpp"
#include "support/scenes.hpp"

using namespace atssim;

namespace {

plan::SubstepPlan serial_plan(int iterations) {
  const auto m =
      model::build_model(scene::parse_scene(test::hanging_cloth_yaml(10, 1e4, 1e-3, iterations), "s.yaml", "."));
  return solver::xpbd::make_xpbd_plan(solver::make_sim_layout(m), {1.0 / 240.0, iterations});
}

// Whether `to` is reachable from `from`.
bool reaches(const sched::TaskGraph& g, sched::TaskId from, sched::TaskId to) {
  std::vector<char> seen(g.size(), 0);
  std::vector<sched::TaskId> stack{from};
  while (!stack.empty()) {
    const auto t = stack.back();
    stack.pop_back();
    if (t == to) return true;
    for (const auto& e : g.successors(t)) {
      if (!seen[e.to]) {
        seen[e.to] = 1;
        stack.push_back(e.to);
      }
    }
  }
  return false;
}

}  // namespace

TEST_CASE("async depth 1 keeps the serial Gauss-Seidel chain") {
  const auto serial = serial_plan(3);
  const auto async = plan::async_graph(serial, 1);
  CHECK(async.graph.edge_count() == serial.graph.edge_count());
  CHECK(async.graph.topological_order() == serial.graph.topological_order());
}

TEST_CASE("async depth n keeps each kind's order and lets at most n iterations overlap") {
  const int iterations = 5, depth = GENERATE(2, 3);
  const auto serial = serial_plan(iterations);
  const auto async = plan::async_graph(serial, depth);
  const auto& g = async.graph;
  REQUIRE(g.size() == serial.graph.size());
  for (const plan::TaskKind& kind : {solver::xpbd::kStretch, solver::xpbd::kBend}) {
    const auto order = sched::gauss_seidel_order(g, kind.label());
    for (std::size_t i = 1; i < order.size(); ++i) CHECK(reaches(g, order[i - 1], order[i]));
  }
  // Iteration k needs all of iteration k - depth, but nothing of k - depth + 1 of the other kind.
  const auto stretch = sched::gauss_seidel_order(g, solver::xpbd::kStretch.label());
  const auto bend = sched::gauss_seidel_order(g, solver::xpbd::kBend.label());
  auto first_of = [&](const std::vector<sched::TaskId>& o, int it) {
    for (auto t : o)
      if (g.task(t).iteration == it) return t;
    return sched::kNoTask;
  };
  auto last_of = [&](const std::vector<sched::TaskId>& o, int it) {
    sched::TaskId last = sched::kNoTask;
    for (auto t : o)
      if (g.task(t).iteration == it) last = t;
    return last;
  };
  for (int it = depth; it < iterations; ++it) {
    CHECK(reaches(g, last_of(bend, it - depth), first_of(stretch, it)));
    CHECK_FALSE(reaches(g, first_of(bend, it - depth + 1), first_of(stretch, it)));
  }
  // Predict before everything, update velocity after everything.
  const auto predict = g.tasks_of_kind(plan::TaskKind::predict.label()).front();
  const auto update = g.tasks_of_kind(plan::TaskKind::update_velocity.label()).front();
  for (sched::TaskId t = 0; t < g.size(); ++t) {
    if (t != predict) CHECK(reaches(g, predict, t));
    if (t != update) CHECK(reaches(g, t, update));
  }
}
