#pragma once
// PEFT, Predict Earliest Finish Time (Arabnejad & Barbosa 2014).
// Optimistic cost table:
//   OCT(i, p) = max over successors j of
//               min over devices w of (OCT(j, w) + w(j, w) + comm(i→j, p→w)),
//   OCT(exit, p) = 0.
// The paper uses the mean comm c̄ (0 when w = p); we use the link's actual
// p → w cost, which is the same for uniform links. Priority rank_oct = mean
// OCT over the devices that can run the task, highest first from the ready
// list; each task goes to the device minimising EFT + OCT (ties: lower
// EFT, then lower device id).
#include "sched/list_scheduling.hpp"

namespace atssim::sched {

// The OCT as a task × device table (ms).
CostTable optimistic_cost_table(const TaskGraph& graph, const CostTable& costs, const DeviceLinks& links);

Schedule schedule_peft(const TaskGraph& graph, const CostTable& costs, const DeviceLinks& links,
                       const ListOptions& options = {});

}  // namespace atssim::sched
