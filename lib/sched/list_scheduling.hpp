#pragma once
// The machinery HEFT, CPOP and PEFT share: per-device timelines, the time a
// task's inputs are ready on a device, its earliest insertion-based start and
// finish, placing it, and the ready list in priority order.
#include <cstdint>
#include <queue>
#include <span>
#include <vector>

#include "sched/compact_graph.hpp"
#include "sched/cost_table.hpp"
#include "sched/device_links.hpp"
#include "sched/device_timeline.hpp"
#include "sched/schedule.hpp"
#include "sched/task_graph.hpp"

namespace atssim::sched {

// Options every list scheduler takes.
struct ListOptions {
  // Per device, busy until this time (ms): re-scheduling onto devices that
  // still run earlier work until t0. Empty: all devices free at 0.
  std::vector<double> device_ready_ms;
  // Topcuoglu 2002 insertion-based policy: a task may fill an idle gap
  // between tasks already placed. Off: it goes after the device's last task.
  bool insertion = true;
};

struct SlotChoice {
  DeviceId device = kNoDevice;
  double start_ms = 0.0;
  double finish_ms = kCannotRun;
};

class ScheduleBuilder {
 public:
  ScheduleBuilder(const TaskGraph& graph, const CompactGraph& compact, const CostTable& costs, const DeviceLinks& links,
                  const ListOptions& options);

  // Earliest start/finish of `task` on `device`, given the tasks placed so
  // far; all its predecessors must be placed. finish = inf where it cannot run.
  SlotChoice earliest_finish(TaskId task, DeviceId device) const;
  // Same for every device at once (one pass over the predecessors).
  void earliest_finish_all(TaskId task, std::vector<SlotChoice>& out) const;

  void place(TaskId task, const SlotChoice& choice);
  bool placed(TaskId task) const { return device_[task] != kNoDevice; }

  Schedule finish() &&;

 private:
  double data_ready(TaskId task, DeviceId device) const;

  const TaskGraph& graph_;
  const CompactGraph& compact_;
  const CostTable& costs_;
  const DeviceLinks& links_;
  bool insertion_;
  std::vector<DeviceTimeline> timelines_;
  std::vector<DeviceId> device_;
  std::vector<double> finish_;
  std::vector<std::vector<Slot>> slots_;
  std::vector<double> ready_ms_;
  std::vector<TaskId> order_;
  mutable std::vector<double> scratch_ready_;
};

// The tasks whose predecessors are all placed, highest priority first; ties
// go to the smaller task id (deterministic). Priorities are
// compared after rounding to 1e-9 ms, so ranks that are equal on paper but
// differ by floating-point rounding (80 = 14.333… + 23 + 42.666…) still tie.
// Call pop(), then place the task, before the next pop().
//
// When the priorities never increase along an edge (always so for rank_u
// and the Gauss-Seidel rank), the whole task list sorted by priority is
// already a topological order, and popping the best ready task yields
// exactly that list; it is then served from the sorted array. Otherwise
// (PEFT's rank_oct at times, CPOP's rank_u + rank_d often) a heap of the
// ready tasks is used.
class ReadyList {
 public:
  ReadyList(const CompactGraph& graph, std::span<const double> priority);
  bool empty() const { return sorted_.empty() ? heap_.empty() : next_ == sorted_.size(); }
  TaskId pop();  // removes the best ready task and releases its successors

 private:
  bool sorted_is_topological() const;
  // The list's total order: higher rounded priority, then smaller id.
  bool before(TaskId a, TaskId b) const { return rounded_[a] > rounded_[b] || (rounded_[a] == rounded_[b] && a < b); }

  struct Entry {
    double priority;
    TaskId task;
  };
  struct Worse {
    bool operator()(const Entry& a, const Entry& b) const {
      return a.priority < b.priority || (a.priority == b.priority && a.task > b.task);
    }
  };
  const CompactGraph& graph_;
  std::vector<double> rounded_;
  std::vector<std::uint32_t> waiting_;
  std::priority_queue<Entry, std::vector<Entry>, Worse> heap_;
  std::vector<TaskId> sorted_;  // non-empty: serve from here
  std::size_t next_ = 0;
};

}  // namespace atssim::sched
