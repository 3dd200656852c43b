#pragma once
// What a solver hands the executor: the buffers it needs (by role), the task
// graph of one substep, and for every task the kernel launches that perform
// it. The contract between solvers and executors; knows no physics
// (DESIGN.md "plan/").
#include <string>
#include <vector>

#include "plan/buffer.hpp"
#include "plan/kernel_launch.hpp"
#include "plan/task_kind.hpp"
#include "sched/task_graph.hpp"

namespace atssim::plan {

struct SubstepPlan {
  std::string program;  // embedded OpenCL program that holds the task functions, e.g. "xpbd"
  std::vector<BufferSpec> buffers;
  sched::TaskGraph graph;                           // labels are TaskKind::label()s
  std::vector<std::vector<KernelLaunch>> launches;  // indexed by task id
  int particle_count = 0;
  // Non-empty: the plan is for one device (schedule single), and this says
  // why (XPBD's solver.ordering: batches sweeps a whole set in one task).
  std::string one_device_reason;

  BufferId add_buffer(std::string name, BufferRole role, std::vector<std::byte> initial);
  // Appends a task with its launches; returns its id.
  sched::TaskId add_task(sched::Task task, std::vector<KernelLaunch> task_launches);
  // Appends a task of `kind` whose one launch follows `after` (if any).
  sched::TaskId add_task_after(sched::TaskId after, sched::Task task, KernelLaunch launch);

  // The one buffer of `role`; throws atssim::Error when there is none or
  // several (a plan has one positions buffer, at most one velocities …).
  BufferId buffer(BufferRole role) const;
  // The one buffer of `role`, or -1 when the plan has none.
  BufferId find_buffer(BufferRole role) const;
  // The tasks of `kind`, in id order.
  std::vector<sched::TaskId> tasks_of(const TaskKind& kind) const { return graph.tasks_of_kind(kind.label()); }
};

}  // namespace atssim::plan
