#pragma once
// Where the tasks of an asynchronous Gauss-Seidel substep run (He et al.
// 2025 §4.1.2, §4.2): HEFT with the Gauss-Seidel rank places the blocks of
// the relaxed graph (plan::async_graph), and the sync map decides which
// results each device merges. Pure: a plan and cost tables in, a placement
// out; plan::make_async_plan turns it into the plan the devices run.
#include "plan/substep_plan.hpp"
#include "sched/cost_table.hpp"
#include "sched/device_links.hpp"
#include "sched/schedule.hpp"
#include "sched/sync_map.hpp"

namespace atssim::plan {

struct AsyncPlacement {
  sched::DeviceId main_device = 0;  // keeps the stream: runs every task outside the iterations
  sched::Schedule placed;           // HEFT's schedule of the relaxed graph
  sched::SyncMap map;
};

// `relaxed` is the async graph's plan, `costs` what each of its tasks costs
// each device (measured on the plan it was relaxed from: async_graph keeps
// the task ids), `hop` the devices' links. The main device is the one with
// the least total cost; the tasks outside the iterations (predict, the
// velocity update) are pinned to it, as they read and write the state no
// other device has. A hop between devices also publishes and merges a whole
// copy of the positions, priced as two predict sweeps on the main device.
// Every Gauss-Seidel kind (plan::traits) keeps its order across iterations.
// `latest`: the sync map also merges the latest result another device
// finished by a task's predicted start (solver.async_fetch: latest).
AsyncPlacement place_async(const SubstepPlan& relaxed, sched::CostTable costs, const sched::DeviceLinks& hop,
                           bool latest);

}  // namespace atssim::plan
