#pragma once
// Turns a scheduled asynchronous Gauss-Seidel graph into a plan the devices
// can run (He et al. 2025 §4.2): each device iterates on its own copy of the
// positions, and the sync map's merges become tasks:
//   publish(P): right after P, P's device snapshots its copy into a slot;
//   merge(T<-P): right before T, T's device merges that snapshot into its
//   copy, from the explicit start point's snapshot, by the chosen strategy.
// Every data flow is an edge, so the result does not depend on timing: an
// executed async schedule and its replay on one device agree exactly.
#include <string>
#include <vector>

#include "plan/substep_plan.hpp"
#include "sched/schedule.hpp"
#include "sched/sync_map.hpp"

namespace atssim::plan {

enum class MergeStrategy { average_positions, average_displacements, main_precedence };

MergeStrategy parse_merge_strategy(const std::string& text);  // throws input errors
std::string to_string(MergeStrategy strategy);

struct AsyncPlan {
  SubstepPlan plan;                     // the graph's tasks (on per-device copies) + publish/merge tasks
  std::vector<sched::DeviceId> device;  // per task of `plan`
  int slots = 0;                        // snapshot buffers allocated
};

// `graph_plan` holds the async graph (plan::async_graph) whose tasks
// `schedule` places; its positions buffer (float4 per particle) is
// replicated per device here.
AsyncPlan make_async_plan(const SubstepPlan& graph_plan, const sched::Schedule& schedule, const sched::SyncMap& map,
                          MergeStrategy strategy);

}  // namespace atssim::plan
