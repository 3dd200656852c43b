// Schedule::validate — an independent check of any schedule against the
// problem it claims to solve (precedence, communication delays, no overlap).
#include <algorithm>
#include <cmath>

#include <fmt/format.h>

#include "sched/schedule.hpp"
#include "util/error.hpp"

namespace atssim::sched {

namespace {

const std::string& name_of(const TaskGraph& graph, TaskId t) { return graph.task(t).name; }

// The slot `placement` points to, or nullptr when it points nowhere valid.
const Slot* placed_slot(const Schedule& s, TaskId t) {
  if (t >= s.placement.size()) return nullptr;
  const Placement& p = s.placement[t];
  if (p.device >= s.devices.size() || p.index >= s.devices[p.device].size()) return nullptr;
  const Slot& slot = s.devices[p.device][p.index];
  return slot.task == t ? &slot : nullptr;
}

void check_shapes(const Schedule& s, const TaskGraph& graph, const CostTable& costs, const DeviceLinks& links,
                  std::vector<std::string>& problems) {
  if (s.placement.size() != graph.size()) {
    problems.push_back(fmt::format("schedule covers {} tasks, the graph has {}", s.placement.size(), graph.size()));
  }
  if (s.devices.size() != costs.devices || s.devices.size() != links.devices) {
    problems.push_back(fmt::format("schedule has {} devices, the cost table {}, the links {}", s.devices.size(),
                                   costs.devices, links.devices));
  }
  if (costs.tasks != graph.size()) {
    problems.push_back(fmt::format("cost table has {} tasks, the graph {}", costs.tasks, graph.size()));
  }
}

void check_slots(const Schedule& s, const TaskGraph& graph, const CostTable& costs, double tol,
                 std::vector<std::string>& problems) {
  std::vector<int> seen(graph.size(), 0);
  double latest = 0.0;
  for (DeviceId d = 0; d < s.devices.size(); ++d) {
    const double ready = d < s.device_ready_ms.size() ? s.device_ready_ms[d] : 0.0;
    const auto& slots = s.devices[d];
    for (std::size_t i = 0; i < slots.size(); ++i) {
      const Slot& slot = slots[i];
      latest = std::max(latest, slot.finish_ms);
      if (slot.task >= graph.size()) {
        problems.push_back(fmt::format("device {} slot {} names task {}, which does not exist", d, i, slot.task));
        continue;
      }
      ++seen[slot.task];
      const std::string& name = name_of(graph, slot.task);
      const Placement& p = slot.task < s.placement.size() ? s.placement[slot.task] : Placement{};
      if (p.device != d || p.index != i) {
        problems.push_back(fmt::format("placement of '{}' does not point to device {} slot {}", name, d, i));
      }
      if (d < costs.devices && slot.task < costs.tasks) {
        const double cost = costs.at(slot.task, d);
        if (!(cost < kCannotRun)) {
          problems.push_back(fmt::format("'{}' is on device {}, which cannot run it", name, d));
        } else if (std::abs((slot.finish_ms - slot.start_ms) - cost) > tol) {
          problems.push_back(fmt::format("'{}' on device {} runs {} ms, its cost is {} ms", name, d,
                                         slot.finish_ms - slot.start_ms, cost));
        }
      }
      if (slot.start_ms < ready - tol) {
        problems.push_back(
            fmt::format("'{}' starts at {} ms, device {} is busy until {} ms", name, slot.start_ms, d, ready));
      }
      if (i > 0 && slot.start_ms < slots[i - 1].finish_ms - tol) {
        problems.push_back(
            fmt::format("'{}' on device {} starts at {} ms, before '{}' finishes "
                        "at {} ms",
                        name, d, slot.start_ms, name_of(graph, slots[i - 1].task), slots[i - 1].finish_ms));
      }
    }
  }
  for (TaskId t = 0; t < graph.size(); ++t) {
    if (seen[t] != 1) {
      problems.push_back(fmt::format("'{}' is scheduled {} times", name_of(graph, t), seen[t]));
    }
  }
  if (std::abs(latest - s.makespan_ms) > tol) {
    problems.push_back(fmt::format("makespan is {} ms, the latest finish is {} ms", s.makespan_ms, latest));
  }
}

void check_edges(const Schedule& s, const TaskGraph& graph, const DeviceLinks& links, double tol,
                 std::vector<std::string>& problems) {
  for (TaskId v = 0; v < graph.size(); ++v) {
    const Slot* sv = placed_slot(s, v);
    if (sv == nullptr) continue;
    const DeviceId q = s.placement[v].device;
    for (const Edge& e : graph.predecessors(v)) {
      const Slot* su = placed_slot(s, e.from);
      if (su == nullptr) continue;
      const DeviceId p = s.placement[e.from].device;
      const double comm = (p < links.devices && q < links.devices) ? links.comm_ms(e.comm, p, q) : 0.0;
      if (sv->start_ms < su->finish_ms + comm - tol) {
        problems.push_back(fmt::format(
            "'{}' (device {}) starts at {} ms, before its input from "
            "'{}' (device {}) is ready at {} ms (finish {} + comm {})",
            name_of(graph, v), q, sv->start_ms, name_of(graph, e.from), p, su->finish_ms + comm, su->finish_ms, comm));
      }
    }
  }
}

}  // namespace

std::vector<std::string> Schedule::validate(const TaskGraph& graph, const CostTable& costs,
                                            const DeviceLinks& links) const {
  std::vector<std::string> problems;
  const double tol = 1e-9 * std::max(1.0, std::abs(makespan_ms));
  check_shapes(*this, graph, costs, links, problems);
  check_slots(*this, graph, costs, tol, problems);
  check_edges(*this, graph, links, tol, problems);
  return problems;
}

void Schedule::throw_if_invalid(const TaskGraph& graph, const CostTable& costs, const DeviceLinks& links) const {
  const auto problems = validate(graph, costs, links);
  if (problems.empty()) return;
  std::string message = fmt::format("invalid schedule ({} problems):", problems.size());
  for (const auto& p : problems) message += "\n  " + p;
  throw internal_error(message);
}

}  // namespace atssim::sched
