#pragma once
// A DAG of coarse simulation tasks (paper §3.3.1). Plain data: a task is an
// id, a name, a kind and its place in the iteration; edges carry the
// communication weight paid when the two ends run on different devices.
// Knows nothing of OpenCL, physics or files: a kind is a label that the layer
// above defines (plan::TaskKind); the scheduler only compares labels.
#include <span>
#include <string>
#include <vector>

#include "sched/ids.hpp"

namespace atssim::sched {

struct Task {
  std::string name;    // unique, human readable: "it2/stretch/c3"
  int kind = 0;        // label shared by the tasks of one kind; kMixedKind for a merge of kinds
  int iteration = -1;  // solver iteration the task belongs to; -1 = none
  int block = -1;      // color block within its kind; -1 = none
  int part = -1;       // part of a task cut between devices (0, 1, …); -1 = the task whole
};

inline constexpr int kMixedKind = -1;

struct Edge {
  TaskId from = 0;
  TaskId to = 0;
  // Communication weight paid when `from` and `to` run on different devices.
  // DeviceLinks turns it into milliseconds (latency + weight × ms_per_weight);
  // with the classic links (DeviceLinks::weighted) it *is* the cost in ms.
  double comm = 0.0;
};

class TaskGraph {
 public:
  TaskId add_task(Task task);
  // Adds from → to. A repeated edge keeps the larger weight.
  void add_edge(TaskId from, TaskId to, double comm = 0.0);

  std::size_t size() const { return tasks_.size(); }
  bool empty() const { return tasks_.empty(); }
  const Task& task(TaskId id) const { return tasks_.at(id); }
  std::span<const Task> tasks() const { return tasks_; }
  std::span<const Edge> successors(TaskId id) const { return out_.at(id); }
  std::span<const Edge> predecessors(TaskId id) const { return in_.at(id); }
  std::size_t edge_count() const;

  // Ids of tasks whose kind equals `kind`, in id order.
  std::vector<TaskId> tasks_of_kind(int kind) const;

  // Kahn's algorithm; ties broken by smallest id, so the order is
  // deterministic. Throws atssim::Error naming the tasks of a cycle.
  std::vector<TaskId> topological_order() const;

 private:
  std::vector<Task> tasks_;
  std::vector<std::vector<Edge>> out_;
  std::vector<std::vector<Edge>> in_;
};

}  // namespace atssim::sched
