#include "sched/task_graph.hpp"

#include <algorithm>
#include <functional>
#include <queue>

#include <fmt/format.h>

#include "util/error.hpp"

namespace atssim::sched {

TaskId TaskGraph::add_task(Task task) {
  tasks_.push_back(std::move(task));
  out_.emplace_back();
  in_.emplace_back();
  return static_cast<TaskId>(tasks_.size() - 1);
}

void TaskGraph::add_edge(TaskId from, TaskId to, double comm) {
  if (from >= size() || to >= size()) {
    throw internal_error(
        fmt::format("task graph: edge {} -> {} names a task that does not exist ({} tasks)", from, to, size()));
  }
  if (from == to) {
    throw internal_error(fmt::format("task graph: task '{}' cannot depend on itself", tasks_[from].name));
  }
  for (Edge& e : out_[from]) {
    if (e.to == to) {
      e.comm = std::max(e.comm, comm);
      for (Edge& r : in_[to]) {
        if (r.from == from) r.comm = e.comm;
      }
      return;
    }
  }
  out_[from].push_back({from, to, comm});
  in_[to].push_back({from, to, comm});
}

std::size_t TaskGraph::edge_count() const {
  std::size_t n = 0;
  for (const auto& edges : out_) n += edges.size();
  return n;
}

std::vector<TaskId> TaskGraph::tasks_of_kind(int kind) const {
  std::vector<TaskId> ids;
  for (TaskId i = 0; i < size(); ++i) {
    if (tasks_[i].kind == kind) ids.push_back(i);
  }
  return ids;
}

namespace {

// Finds one cycle among the tasks Kahn's algorithm could not order, by
// walking predecessors until a task repeats.
std::vector<TaskId> find_cycle(const TaskGraph& graph, const std::vector<int>& indegree) {
  TaskId start = 0;
  while (indegree[start] == 0) ++start;
  std::vector<int> seen_at(graph.size(), -1);
  std::vector<TaskId> path;
  TaskId current = start;
  while (seen_at[current] < 0) {
    seen_at[current] = static_cast<int>(path.size());
    path.push_back(current);
    for (const Edge& e : graph.predecessors(current)) {
      if (indegree[e.from] > 0) {
        current = e.from;
        break;
      }
    }
  }
  std::vector<TaskId> cycle(path.begin() + seen_at[current], path.end());
  std::reverse(cycle.begin(), cycle.end());
  return cycle;
}

}  // namespace

std::vector<TaskId> TaskGraph::topological_order() const {
  std::vector<int> indegree(size(), 0);
  for (TaskId i = 0; i < size(); ++i) indegree[i] = static_cast<int>(in_[i].size());
  std::priority_queue<TaskId, std::vector<TaskId>, std::greater<>> ready;
  for (TaskId i = 0; i < size(); ++i) {
    if (indegree[i] == 0) ready.push(i);
  }
  std::vector<TaskId> order;
  order.reserve(size());
  while (!ready.empty()) {
    const TaskId id = ready.top();
    ready.pop();
    order.push_back(id);
    for (const Edge& e : out_[id]) {
      if (--indegree[e.to] == 0) ready.push(e.to);
    }
  }
  if (order.size() != size()) {
    std::string names;
    const auto cycle = find_cycle(*this, indegree);
    for (TaskId id : cycle) names += tasks_[id].name + " -> ";
    names += tasks_[cycle.front()].name;
    throw internal_error("task graph has a cycle: " + names);
  }
  return order;
}

}  // namespace atssim::sched
