#pragma once
// Cuts the launches of a SubstepPlan into parts that may run on different
// devices. A task with one launch is cut by its range; a task of several
// launches stays whole. The result computes exactly what the plan computes,
// in the same Gauss-Seidel order: every part of a task depends on every part
// of the task's predecessors.
#include <span>

#include "plan/substep_plan.hpp"

namespace atssim::plan {

// `fractions` (positive, summed to 1) gives each part's share of the elements;
// boundaries are rounded to multiples of `granule` elements so that every
// part but the last fills whole work-groups. Empty parts are dropped. Part k
// of task "it1/stretch/c0" is named "it1/stretch/c0#k" and has Task::part k.
SubstepPlan split_plan(const SubstepPlan& plan, std::span<const double> fractions, std::size_t granule = 64);

// Moves the boundaries between the parts of a split plan to `fractions`
// (one per part), as split_plan would have cut: the tasks, their devices and
// edges stay; only the parts' ranges change (a part may become empty).
// Returns the new share of every task, per task id: its elements over the
// elements of its whole (1 for tasks that are not parts).
std::vector<double> recut_plan(SubstepPlan& plan, std::span<const double> fractions, std::size_t granule = 64);

// Where the boundaries between parts fall, for an executor whose launches run
// `work_group_elements` elements per work-group (one work-item each): on
// whole work-groups, so that no group straddles two parts. An executor whose
// work-groups each take a contiguous share (0: the fused dispatcher) has no
// group to fill and cuts finer, on multiples of 8 elements.
std::size_t part_granule(std::size_t work_group_elements);

}  // namespace atssim::plan
