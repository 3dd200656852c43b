#pragma once
// HEFT, Heterogeneous Earliest Finish Time (Topcuoglu, Hariri & Wu 2002;
// paper §3.3). Tasks in decreasing rank_u; each goes to the device where it
// finishes earliest, allowing insertion into idle gaps.
//
// Tie-breaking (deterministic): equal ranks → the task earlier in
// TaskGraph::topological_order() (Kahn, smallest id first); equal finish
// times → the lowest device id.
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

}  // namespace atssim::sched
