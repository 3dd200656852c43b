#include "plan/task_work.hpp"

namespace atssim::plan {

double work_per_item_us(TaskKind kind) {
  // Profiled per element or particle (bench/profile_task_kinds, the 64×64
  // hanging cloth and the 48×48 drape for collision and friction).
  switch (kind) {
    case TaskKind::predict:
      return 0.0016;
    case TaskKind::stretch:
      return 0.010;
    case TaskKind::bend:
      return 0.016;
    case TaskKind::tet:
      return 0.142;
    case TaskKind::vertex:
      return 0.314;
    case TaskKind::jacobi:
      return 0.296;
    case TaskKind::systems:
      return 0.355;
    case TaskKind::main_block:
      return 0.132;
    case TaskKind::stencils:
      return 0.259;
    case TaskKind::combine:
      return 0.052;
    case TaskKind::collision:
      return 0.005;
    case TaskKind::copy:
      return 0.001;
    case TaskKind::update_velocity:
      return 0.00075;
    case TaskKind::publish:
    case TaskKind::merge:
      return 0.002;
    case TaskKind::energy:
      return 0.020;
    case TaskKind::friction:
      return 0.009;
    case TaskKind::detection:
      return 0.050;
  }
  return 0.0;
}

double task_work_us(const SubstepPlan& plan, sched::TaskId task, const WorkWeights& weights) {
  double items = 0.0;
  for (const KernelLaunch& l : plan.launches.at(task)) items += l.range.count;
  const sched::Task& t = plan.graph.task(task);
  // A task merged from several kinds (no solver's plan has one) counts at
  // the heaviest weight, so the model does not underrate it.
  const double per_item =
      t.kind == sched::kMixedKind ? work_per_item_us(TaskKind::systems) : work_per_item_us(kind_of(t));
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
