#pragma once
// Cuts the launches of a SubstepPlan into parts that may run on different
// devices. Only launches that declare a range of independent elements
// (KernelLaunch::range_arg) are cut; the rest stay whole. The result
// computes exactly what the plan computes, in the same Gauss-Seidel order:
// every part of a task depends on every part of the task's predecessors.
#include <span>

#include "solver/substep_plan.hpp"

namespace atssim::solver {

// `fractions` (positive, summed to 1) gives each part's share of the elements;
// boundaries are rounded to multiples of `granule` work-items so that every
// part but the last fills whole work-groups. Empty parts are dropped. Part k
// of task "it1/stretch/c0" is named "it1/stretch/c0#k".
SubstepPlan split_plan(const SubstepPlan& plan, std::span<const double> fractions, std::size_t granule = 64);

// Index of the part a task of a split plan holds (its "#k" suffix), or -1.
int part_of(const sched::Task& task);

}  // namespace atssim::solver
