#include "plan/task_work.hpp"

#include <string_view>

namespace atssim::plan {

namespace {

// Profiled per element or particle (bench/profile_task_kinds, the 64×64
// hanging cloth and the 48×48 drape for collision and friction), by kind
// name: the shared kinds (plan/task_kind.hpp) and the methods' own.
struct KindWork {
  std::string_view kind;
  double us;
};
constexpr KindWork kWork[] = {
    {"predict", 0.0016},
    {"stretch", 0.010},
    {"bend", 0.016},
    {"tet", 0.142},
    {"vertex", 0.314},
    {"jacobi", 0.296},
    {"systems", 0.355},
    {"main_block", 0.132},
    {"stencils", 0.259},
    {"combine", 0.052},
    {"collision", 0.005},
    {"copy", 0.001},
    {"update_velocity", 0.00075},
    {"publish", 0.002},
    {"merge", 0.002},
    {"energy", 0.020},
    {"friction", 0.009},
    {"detection", 0.050},
};
// A kind nobody profiled (a new method's) counts at the heaviest weight, so
// the model does not underrate it.
constexpr double kHeaviest = 0.355;

}  // namespace

double work_per_item_us(const TaskKind& kind) {
  for (const KindWork& w : kWork) {
    if (w.kind == kind.name()) return w.us;
  }
  return kHeaviest;
}

double task_work_us(const SubstepPlan& plan, sched::TaskId task, const WorkWeights& weights) {
  double items = 0.0;
  for (const KernelLaunch& l : plan.launches.at(task)) items += l.range.count;
  const sched::Task& t = plan.graph.task(task);
  // A task merged from several kinds (no solver's plan has one) counts at
  // the heaviest weight, so the model does not underrate it.
  const double per_item = t.kind == sched::kMixedKind ? kHeaviest : work_per_item_us(kind_of(t));
  return weights.task_us + items * per_item;
}

sched::CostTable work_cost_table(const SubstepPlan& plan, std::span<const double> ms_per_us,
                                 const WorkWeights& weights) {
  sched::CostTable costs(plan.graph.size(), ms_per_us.size());
  for (sched::TaskId t = 0; t < plan.graph.size(); ++t) {
    const double us = task_work_us(plan, t, weights);
    for (std::size_t d = 0; d < ms_per_us.size(); ++d) costs.at(t, d) = us * ms_per_us[d];
  }
  return costs;
}

}  // namespace atssim::plan
