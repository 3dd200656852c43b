#pragma once
// The copies a schedule needs when every device has a memory of its own
// (DESIGN.md "Devices": devices of different platforms share no SVM, and
// `--memory separate` makes even one platform's devices work that way).
// Pure: from the order the devices run the tasks in and what each task
// writes, which bytes move from which device to which, and when.
#include <span>
#include <vector>

#include "plan/element_sets.hpp"
#include "sched/ids.hpp"
#include "sched/task_graph.hpp"

namespace atssim::plan {

// One task in the order an executor starts them: on which device, and the
// tasks of other devices it must wait for within the substep (each
// device's first task also waits for every other device's last task of the
// substep before).
struct ExecutionStep {
  sched::TaskId task = 0;
  std::size_t device = 0;
  std::vector<sched::TaskId> waits;

  friend bool operator==(const ExecutionStep&, const ExecutionStep&) = default;
};

// After `producer` ends on `from`, `elements` go from `from`'s memory to
// `to`'s, before step `before` (an index into the steps) runs on `to`.
struct Transfer {
  std::size_t from = 0, to = 0;
  sched::TaskId producer = 0;
  std::size_t before = 0;
  ElementSets elements;
};

struct TransferPlan {
  // At the cross-device waits of a substep, in step order.
  std::vector<Transfer> within;
  // What is left after each device's last task (producer = that task), for
  // every other device: it moves at the substep boundary, before the next
  // substep's first task there (and at the end of a run, so that every
  // memory holds the whole state again). `before` is the steps' count.
  std::vector<Transfer> boundary;

  std::size_t bytes_per_substep() const;
};

// Every device has its own memory, and the substep starts with all of them
// equal. Walking the steps, what a device writes queues up for every other
// device; when device d waits for task p of device o, everything o wrote or
// received up to p that d has not had moves to d (what d receives queues up
// for the devices after it: data may reach a device through another one).
// `written[t]` is what task t writes (written_elements of its launches).
TransferPlan plan_transfers(std::span<const ExecutionStep> steps, std::span<const ElementSets> written,
                            std::size_t devices);

// DESIGN.md: an edge weighs the bytes its producer writes (only links between
// memories price them, DeviceLinks::ms_per_weight). Raises every edge from
// task t to written[t].bytes(); a heavier weight stays (TaskGraph::add_edge).
void weigh_edges_by_writes(sched::TaskGraph& graph, std::span<const ElementSets> written);

}  // namespace atssim::plan
