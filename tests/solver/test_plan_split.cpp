#include <catch2/catch.hpp>

#include <map>

#include "model/cloth_builder.hpp"
#include "scene/scene_loader.hpp"
#include "solver/plan_split.hpp"
#include "solver/xpbd/xpbd_plan.hpp"
#include "support/scenes.hpp"

using namespace atssim;

namespace {

solver::SubstepPlan cloth_plan() {
  const auto m = model::build_model(scene::parse_scene(test::hanging_cloth_yaml(40), "s.yaml", "."));
  return solver::xpbd::make_xpbd_plan(solver::make_sim_layout(m), {1.0 / 240.0, 2});
}

// (kernel, first element) -> count, over every launch of the plan.
std::map<std::pair<std::string, int>, int> coverage(const solver::SubstepPlan& plan) {
  std::map<std::pair<std::string, int>, int> out;
  for (const auto& launches : plan.launches) {
    for (const auto& l : launches) {
      if (l.range_arg < 0) continue;
      const int first = l.args[l.range_arg].i32;
      const int count = l.args[l.range_arg + 1].i32;
      for (int e = first; e < first + count; ++e) out[{l.kernel + "/" + std::to_string(l.args[1].buffer), e}] += 1;
    }
  }
  return out;
}

}  // namespace

TEST_CASE("split parts cover every element of every launch exactly once") {
  const auto plan = cloth_plan();
  const std::vector<double> fractions = GENERATE(std::vector<double>{0.5, 0.5}, std::vector<double>{0.3, 0.7},
                                                 std::vector<double>{0.2, 0.3, 0.5});
  const auto split = solver::split_plan(plan, fractions);
  CHECK(coverage(split) == coverage(plan));
  CHECK(split.graph.size() > plan.graph.size());
}

TEST_CASE("every part of a task depends on every part of its predecessor") {
  const auto plan = cloth_plan();
  const std::vector<double> halves{0.5, 0.5};
  const auto split = solver::split_plan(plan, halves);
  // Group the split tasks by the task they came from (name without "#k").
  std::map<std::string, std::vector<sched::TaskId>> by_origin;
  for (sched::TaskId t = 0; t < split.graph.size(); ++t) {
    const std::string& name = split.graph.task(t).name;
    by_origin[name.substr(0, name.rfind('#'))].push_back(t);
  }
  CHECK(by_origin.size() == plan.graph.size());
  for (sched::TaskId t = 0; t < plan.graph.size(); ++t) {
    for (const auto& e : plan.graph.successors(t)) {
      for (sched::TaskId a : by_origin[plan.graph.task(t).name]) {
        for (sched::TaskId b : by_origin[plan.graph.task(e.to).name]) {
          bool found = false;
          for (const auto& s : split.graph.successors(a)) found = found || s.to == b;
          CHECK(found);
        }
      }
    }
  }
}

TEST_CASE("part boundaries fall on whole work-groups and parts follow their fractions") {
  const auto plan = cloth_plan();
  const std::vector<double> fractions{0.25, 0.75};
  const auto split = solver::split_plan(plan, fractions, 64);
  for (sched::TaskId t = 0; t < split.graph.size(); ++t) {
    const auto& task = split.graph.task(t);
    if (solver::part_of(task) != 0) continue;
    const auto& l = split.launches[t][0];
    CHECK(l.global_size % 64 == 0);
  }
  CHECK(solver::part_of(split.graph.task(0)) == 0);
  CHECK(solver::part_of(sched::Task{"predict", "predict", -1, -1}) == -1);
}

TEST_CASE("one fraction leaves the plan as it is") {
  const auto plan = cloth_plan();
  const std::vector<double> one{1.0};
  const auto same = solver::split_plan(plan, one);
  CHECK(same.graph.size() == plan.graph.size());
  CHECK(coverage(same) == coverage(plan));
}
