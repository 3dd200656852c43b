#pragma once
// CPOP, Critical Path On a Processor (Topcuoglu, Hariri & Wu 2002 §4.2).
// Priority = rank_u + rank_d. The critical path starts at the entry task of
// highest priority and follows, at each step, a successor whose priority
// equals it (the first in edge order; tolerance 1e-9 relative). All its tasks
// go to the one device that runs the whole path fastest; every other task,
// taken highest priority first from the ready list, goes to the device where
// it finishes earliest (insertion-based). If no device can run every
// critical-path task, those tasks fall back to earliest finish too.
#include <vector>

#include "sched/list_scheduling.hpp"

namespace atssim::sched {

std::vector<TaskId> cpop_critical_path(const TaskGraph& graph, const CostTable& costs, const DeviceLinks& links);

Schedule schedule_cpop(const TaskGraph& graph, const CostTable& costs, const DeviceLinks& links,
                       const ListOptions& options = {});

}  // namespace atssim::sched
