#pragma once
// A deterministic cost of every task of a plan: what its launches do,
// counted (elements or particles per launch) and weighted by its kind, in
// microseconds of the reference device. `run --tolerance` compares its
// choices by this model, not by timings, so that the same scene, devices
// and flags give the same choice on a loaded machine as on a quiet one;
// measured timings only scale it to the devices at hand (app/accuracy_probe).
//
// The weights were profiled on one pocl CPU sub-device (AMD EPYC, fused
// executor, 64×64 hanging cloth; `bench/profile_task_kinds` prints them
// for any scene): per element of a vertex kind (VBD, JPGD, SOSD) the cost
// grows with the elements around a vertex, so on solids (≈17 tets per
// vertex) those kinds cost ~1.8× what the cloth weights say (measured on
// scenes/soft_box.yaml), and every method that gathers per vertex alike.
#include <span>

#include "plan/substep_plan.hpp"
#include "sched/cost_table.hpp"

namespace atssim::plan {

struct WorkWeights {
  double task_us = 1.5;  // every task: the executor's hop to it (fused; events: a launch)
};

// Microseconds per element (or particle) of a launch of `kind` on the
// reference device.
double work_per_item_us(const TaskKind& kind);

// The modelled cost of task `task` of `plan`: task_us + items × weight.
double task_work_us(const SubstepPlan& plan, sched::TaskId task, const WorkWeights& weights = {});

// A cost table (ms) of every task on every device: the modelled cost times
// each device's `ms_per_us` (its speed against the reference device; 1e-3
// for the reference itself).
sched::CostTable work_cost_table(const SubstepPlan& plan, std::span<const double> ms_per_us,
                                 const WorkWeights& weights = {});

}  // namespace atssim::plan
