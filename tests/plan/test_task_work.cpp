#include <catch2/catch.hpp>

#include "plan/split_plan.hpp"
#include "plan/task_work.hpp"

using namespace atssim;

namespace {

// Kinds the methods declare in their folders (solver/xpbd, solver/vbd),
// named alike here: the model weighs a kind by its name.
const plan::TaskKind kStretch{{"stretch", true, false, false}};
const plan::TaskKind kVertex{{"vertex", true, false, true}};

// Two tasks: a predict over 1000 particles, then two stretch blocks of
// 300 and 200 edges (two launches in one task).
plan::SubstepPlan two_task_plan() {
  plan::SubstepPlan p;
  p.add_task(plan::make_task("predict", plan::TaskKind::predict), {{"predict", {0, 1000}, {}, {}}});
  p.add_task(plan::make_task("it1/stretch/c0", kStretch, 0, 0),
             {{"stretch", {0, 300}, {}, {}}, {"stretch", {300, 200}, {}, {}}});
  p.graph.add_edge(0, 1);
  return p;
}

}  // namespace

TEST_CASE("a task's modelled cost is its hop plus its launches' elements times its kind's weight") {
  const plan::SubstepPlan p = two_task_plan();
  const plan::WorkWeights w{2.0};
  CHECK(plan::task_work_us(p, 0, w) == Approx(2.0 + 1000 * plan::work_per_item_us(plan::TaskKind::predict)));
  CHECK(plan::task_work_us(p, 1, w) == Approx(2.0 + 500 * plan::work_per_item_us(kStretch)));
}

TEST_CASE("every kind of task has a positive weight, and a vertex step costs more than a constraint") {
  for (const plan::TaskKind* k :
       {&plan::TaskKind::predict, &plan::TaskKind::jacobi, &plan::TaskKind::collision, &plan::TaskKind::copy,
        &plan::TaskKind::update_velocity, &plan::TaskKind::publish, &plan::TaskKind::merge, &plan::TaskKind::energy,
        &plan::TaskKind::friction, &plan::TaskKind::detection, &kStretch, &kVertex}) {
    INFO(plan::to_string(*k));
    CHECK(plan::work_per_item_us(*k) > 0.0);
  }
  // A VBD vertex gathers every element around it; an XPBD constraint is one.
  CHECK(plan::work_per_item_us(kVertex) > 10 * plan::work_per_item_us(kStretch));
  // A kind nobody profiled counts at least as much as any profiled one.
  const plan::TaskKind unknown{{"a_new_methods_kind", false, false, false}};
  CHECK(plan::work_per_item_us(unknown) >= plan::work_per_item_us(kVertex));
}

TEST_CASE("the cost table scales the model by each device's speed, and a split keeps the total work") {
  const plan::SubstepPlan p = two_task_plan();
  const std::vector<double> speed{1e-3, 2e-3};  // the second device half as fast
  const sched::CostTable t = plan::work_cost_table(p, speed);
  REQUIRE(t.tasks == 2);
  REQUIRE(t.devices == 2);
  CHECK(t.at(1, 0) == Approx(plan::task_work_us(p, 1) * 1e-3));
  CHECK(t.at(1, 1) == Approx(2 * t.at(1, 0)));
  // Cut in halves, the elements are counted once: only the hops add up.
  const plan::SubstepPlan halves = plan::split_plan(p, std::vector<double>{0.5, 0.5});
  double whole = 0.0, parts = 0.0;
  for (sched::TaskId i = 0; i < p.graph.size(); ++i) whole += plan::task_work_us(p, i, {0.0});
  for (sched::TaskId i = 0; i < halves.graph.size(); ++i) parts += plan::task_work_us(halves, i, {0.0});
  CHECK(parts == Approx(whole));
}
