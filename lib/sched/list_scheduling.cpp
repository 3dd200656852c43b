#include "sched/list_scheduling.hpp"

#include <algorithm>
#include <cmath>
#include <numeric>

#include "util/error.hpp"

namespace atssim::sched {

namespace {

// Shortest finite cost of any task on `device`: gaps below it are useless.
double shortest_task(const CostTable& costs, DeviceId device) {
  double shortest = kCannotRun;
  for (TaskId t = 0; t < costs.tasks; ++t) shortest = std::min(shortest, costs.at(t, device));
  return shortest < kCannotRun ? shortest : 0.0;
}

// Rounds a priority to a multiple of 1e-9 ms (see ReadyList).
double tie_rounded(double priority) { return std::round(priority * 1e9); }

}  // namespace

ScheduleBuilder::ScheduleBuilder(const TaskGraph& graph, const CompactGraph& compact, const CostTable& costs,
                                 const DeviceLinks& links, const ListOptions& options)
    : graph_(graph),
      compact_(compact),
      costs_(costs),
      links_(links),
      insertion_(options.insertion),
      device_(graph.size(), kNoDevice),
      finish_(graph.size(), 0.0),
      slots_(costs.devices),
      ready_ms_(options.device_ready_ms),
      scratch_ready_(costs.devices, 0.0) {
  if (ready_ms_.empty()) ready_ms_.assign(costs.devices, 0.0);
  timelines_.reserve(costs.devices);
  for (DeviceId d = 0; d < costs.devices; ++d) {
    timelines_.emplace_back(ready_ms_[d], shortest_task(costs, d));
  }
  order_.reserve(graph.size());
}

double ScheduleBuilder::data_ready(TaskId task, DeviceId device) const {
  double ready = 0.0;
  for (const CompactEdge& e : compact_.predecessors(task)) {
    ready = std::max(ready, finish_[e.task] + links_.comm_ms(e.comm, device_[e.task], device));
  }
  return ready;
}

SlotChoice ScheduleBuilder::earliest_finish(TaskId task, DeviceId device) const {
  const double cost = costs_.at(task, device);
  if (!(cost < kCannotRun)) return {device, 0.0, kCannotRun};
  const double start = timelines_[device].earliest_start(data_ready(task, device), cost, insertion_);
  return {device, start, start + cost};
}

void ScheduleBuilder::earliest_finish_all(TaskId task, std::vector<SlotChoice>& out) const {
  const std::size_t nd = costs_.devices;
  std::fill(scratch_ready_.begin(), scratch_ready_.end(), 0.0);
  for (const CompactEdge& e : compact_.predecessors(task)) {
    const DeviceId p = device_[e.task];
    for (DeviceId d = 0; d < nd; ++d) {
      scratch_ready_[d] = std::max(scratch_ready_[d], finish_[e.task] + links_.comm_ms(e.comm, p, d));
    }
  }
  out.resize(nd);
  for (DeviceId d = 0; d < nd; ++d) {
    const double cost = costs_.at(task, d);
    if (!(cost < kCannotRun)) {
      out[d] = {d, 0.0, kCannotRun};
      continue;
    }
    const double start = timelines_[d].earliest_start(scratch_ready_[d], cost, insertion_);
    out[d] = {d, start, start + cost};
  }
}

void ScheduleBuilder::place(TaskId task, const SlotChoice& choice) {
  if (choice.device >= costs_.devices || !(choice.finish_ms < kCannotRun)) {
    throw internal_error("list scheduling: task '" + graph_.task(task).name + "' has no device to run on");
  }
  timelines_[choice.device].reserve(choice.start_ms, choice.finish_ms);
  device_[task] = choice.device;
  finish_[task] = choice.finish_ms;
  slots_[choice.device].push_back({task, choice.start_ms, choice.finish_ms});
  order_.push_back(task);
}

Schedule ScheduleBuilder::finish() && {
  Schedule s = assemble_schedule(graph_.size(), std::move(slots_), std::move(ready_ms_));
  s.scheduling_order = std::move(order_);
  return s;
}

ReadyList::ReadyList(const CompactGraph& graph, std::span<const double> priority)
    : graph_(graph), rounded_(graph.size()) {
  for (TaskId t = 0; t < graph.size(); ++t) rounded_[t] = tie_rounded(priority[t]);
  if (sorted_is_topological()) {
    sorted_.resize(graph.size());
    std::iota(sorted_.begin(), sorted_.end(), TaskId{0});
    std::sort(sorted_.begin(), sorted_.end(), [&](TaskId a, TaskId b) { return before(a, b); });
    return;
  }
  waiting_.resize(graph.size());
  std::vector<Entry> initial;
  for (TaskId t = 0; t < graph.size(); ++t) {
    waiting_[t] = static_cast<std::uint32_t>(graph.predecessors(t).size());
    if (waiting_[t] == 0) initial.push_back({rounded_[t], t});
  }
  heap_ = decltype(heap_)(Worse{}, std::move(initial));
}

// The sorted list is a topological order iff every edge goes from a task
// that sorts earlier to one that sorts later.
bool ReadyList::sorted_is_topological() const {
  for (TaskId t = 0; t < graph_.size(); ++t) {
    for (const CompactEdge& e : graph_.successors(t)) {
      if (!before(t, e.task)) return false;
    }
  }
  return true;
}

TaskId ReadyList::pop() {
  if (!sorted_.empty()) return sorted_[next_++];
  const TaskId t = heap_.top().task;
  heap_.pop();
  for (const CompactEdge& e : graph_.successors(t)) {
    if (--waiting_[e.task] == 0) heap_.push({rounded_[e.task], e.task});
  }
  return t;
}

}  // namespace atssim::sched
