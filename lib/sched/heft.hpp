#pragma once
// HEFT, Heterogeneous Earliest Finish Time (Topcuoglu, Hariri & Wu 2002;
// paper §3.3). Tasks in decreasing rank_u; each goes to the device where it
// finishes earliest, allowing insertion into idle gaps.
//
// Tasks are taken from a ready list (all predecessors placed), so any
// priority gives a valid schedule; with rank_u this is exactly the classic
// decreasing-rank order. Tie-breaking (deterministic): ranks equal to 1e-9 ms
// → the smaller task id; equal finish times → the lower device id.
#include <vector>

#include "sched/list_scheduling.hpp"

namespace atssim::sched {

struct HeftOptions : ListOptions {
  // One priority per task, higher first (e.g. gauss_seidel_rank()); empty =
  // upward_rank(). A task is only taken once its predecessors are placed, so
  // any priority yields a valid schedule.
  std::vector<double> priority;
};

Schedule schedule_heft(const TaskGraph& graph, const CostTable& costs, const DeviceLinks& links,
                       const HeftOptions& options = {});

// HEFT, or every task on one device where that is predicted to end sooner.
// HEFT places each task by its own finish time; it cannot see that the
// copies its choices force on the tasks after it (slow links between
// memories) cost more than the second device saves. Equal makespans keep
// HEFT's schedule.
Schedule schedule_heft_or_one_device(const TaskGraph& graph, const CostTable& costs, const DeviceLinks& links,
                                     const HeftOptions& options = {});

}  // namespace atssim::sched
