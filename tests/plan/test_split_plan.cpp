#include <catch2/catch.hpp>

#include <map>

#include "model/cloth_builder.hpp"
#include "plan/split_plan.hpp"
#include "scene/scene_loader.hpp"
#include "solver/xpbd/xpbd_plan.hpp"
#include "support/scenes.hpp"

using namespace atssim;

namespace {

plan::SubstepPlan cloth_plan() {
  const auto m = model::build_model(scene::parse_scene(test::hanging_cloth_yaml(40), "s.yaml", "."));
  return solver::xpbd::make_xpbd_plan(solver::make_sim_layout(m), {1.0 / 240.0, 2});
}

// (function/elements buffer, element) -> count, over every launch of the plan.
std::map<std::pair<std::string, int>, int> coverage(const plan::SubstepPlan& plan) {
  std::map<std::pair<std::string, int>, int> out;
  for (const auto& launches : plan.launches) {
    for (const auto& l : launches) {
      const std::string key = l.function + "/" + std::to_string(l.args.size() > 1 ? l.args[1].buffer : -1);
      for (int e = l.range.first; e < l.range.first + l.range.count; ++e) out[{key, e}] += 1;
    }
  }
  return out;
}

}  // namespace

TEST_CASE("split parts cover every element of every launch exactly once") {
  const auto plan = cloth_plan();
  const std::vector<double> fractions =
      GENERATE(std::vector<double>{0.5, 0.5}, std::vector<double>{0.3, 0.7}, std::vector<double>{0.2, 0.3, 0.5});
  const auto split = plan::split_plan(plan, fractions);
  CHECK(coverage(split) == coverage(plan));
  CHECK(split.graph.size() > plan.graph.size());
}

TEST_CASE("every part of a task depends on every part of its predecessor") {
  const auto plan = cloth_plan();
  const std::vector<double> halves{0.5, 0.5};
  const auto split = plan::split_plan(plan, halves);
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

TEST_CASE("part boundaries fall on whole work-groups and each part knows its index") {
  const auto plan = cloth_plan();
  const std::vector<double> fractions{0.25, 0.75};
  const auto split = plan::split_plan(plan, fractions, 64);
  for (sched::TaskId t = 0; t < split.graph.size(); ++t) {
    const auto& task = split.graph.task(t);
    REQUIRE(task.part >= 0);
    CHECK(task.name.substr(task.name.rfind('#') + 1) == std::to_string(task.part));
    if (task.part != 0) continue;
    CHECK(split.launches[t][0].range.count % 64 == 0);
  }
  CHECK(split.graph.task(0).part == 0);
  for (const sched::Task& t : plan.graph.tasks()) CHECK(t.part == -1);
}

TEST_CASE("one fraction leaves the plan as it is") {
  const auto plan = cloth_plan();
  const std::vector<double> one{1.0};
  const auto same = plan::split_plan(plan, one);
  CHECK(same.graph.size() == plan.graph.size());
  CHECK(coverage(same) == coverage(plan));
}

TEST_CASE("recut moves the boundaries between parts and keeps every element covered once") {
  const auto plan = cloth_plan();
  const std::vector<double> halves{0.5, 0.5}, uneven{0.25, 0.75};
  auto split = plan::split_plan(plan, halves, 8);
  const auto tasks = split.graph.size();
  const auto shares = plan::recut_plan(split, uneven, 8);
  CHECK(split.graph.size() == tasks);
  CHECK(coverage(split) == coverage(plan));
  REQUIRE(shares.size() == tasks);
  for (sched::TaskId t = 0; t < tasks; ++t) {
    const auto& task = split.graph.task(t);
    if (task.part < 0) continue;
    const int count = split.launches[t][0].range.count;
    const int whole = count + split.launches[task.part == 0 ? t + 1 : t - 1][0].range.count;
    if (whole < 64) continue;  // rounding to 8 dominates small blocks
    CHECK(shares[t] == Approx(uneven[task.part]).margin(8.0 / whole));
    CHECK(shares[t] == Approx(double(count) / whole));
  }
  // Back to halves: the same cut split_plan makes.
  plan::recut_plan(split, halves, 8);
  const auto again = plan::split_plan(plan, halves, 8);
  for (sched::TaskId t = 0; t < tasks; ++t) {
    CHECK(split.launches[t][0].range.first == again.launches[t][0].range.first);
    CHECK(split.launches[t][0].range.count == again.launches[t][0].range.count);
  }
}

TEST_CASE("a block smaller than a granule still gets one part per fraction, the empty one running nothing") {
  const auto plan = cloth_plan();
  const std::vector<double> halves{0.5, 0.5};
  const auto split = plan::split_plan(plan, halves, 1 << 20);  // every block smaller than the granule
  std::size_t cut = 0;
  for (sched::TaskId t = 0; t < plan.graph.size(); ++t) cut += plan.launches[t].size() == 1 ? 1 : 0;
  CHECK(split.graph.size() == plan.graph.size() + cut);
  for (sched::TaskId t = 0; t < split.graph.size(); ++t) {
    if (split.graph.task(t).part == 0) CHECK(split.launches[t][0].range.count == 0);
  }
  CHECK(coverage(split) == coverage(plan));
}

TEST_CASE("parts end on whole work-groups, or on multiples of 8 where a work-group takes a share") {
  CHECK(plan::part_granule(64) == 64);  // events: one work-item per element, groups of 64
  CHECK(plan::part_granule(32) == 32);
  CHECK(plan::part_granule(0) == 8);  // fused: no group to fill
}
