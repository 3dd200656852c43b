#include "plan/transfer_plan.hpp"

#include <fmt/format.h>

#include "util/error.hpp"

namespace atssim::plan {

namespace {

// Writes (or receipts) of one device not yet shipped to one other device,
// with the position on the source device from which they are available.
struct Pending {
  std::size_t position = 0;  // index of the step on its device after which the bytes are there
  ElementSets elements;
};

}  // namespace

std::size_t TransferPlan::bytes_per_substep() const {
  std::size_t n = 0;
  for (const Transfer& t : within) n += t.elements.bytes();
  for (const Transfer& t : boundary) n += t.elements.bytes();
  return n;
}

TransferPlan plan_transfers(std::span<const ExecutionStep> steps, std::span<const ElementSets> written,
                            std::size_t devices) {
  TransferPlan out;
  // queue[o * devices + d]: what d still needs from o.
  std::vector<std::vector<Pending>> queue(devices * devices);
  std::vector<std::size_t> count_on(devices, 0);  // steps seen per device
  std::vector<std::size_t> position_of(written.size(), 0);
  std::vector<std::size_t> device_of(written.size(), devices);
  std::vector<sched::TaskId> last_on(devices, 0);
  for (std::size_t s = 0; s < steps.size(); ++s) {
    const ExecutionStep& step = steps[s];
    const std::size_t d = step.device;
    if (d >= devices || step.task >= written.size()) {
      throw internal_error(
          fmt::format("transfer plan: step {} names device {} or task {} outside the plan", s, d, step.task));
    }
    const std::size_t here = count_on[d]++;
    for (sched::TaskId p : step.waits) {
      const std::size_t o = device_of.at(p);
      if (o >= devices)
        throw internal_error(fmt::format("transfer plan: task {} waits for task {}, not run before it", step.task, p));
      if (o == d) continue;
      Transfer t{o, d, p, s, {}};
      auto& pending = queue[o * devices + d];
      for (auto it = pending.begin(); it != pending.end();) {
        if (it->position <= position_of[p]) {
          t.elements.add(it->elements);
          it = pending.erase(it);
        } else {
          ++it;
        }
      }
      if (t.elements.empty()) continue;
      for (std::size_t x = 0; x < devices; ++x) {
        if (x != d && x != o) queue[d * devices + x].push_back({here, t.elements});
      }
      out.within.push_back(std::move(t));
    }
    position_of[step.task] = here;
    device_of[step.task] = d;
    last_on[d] = step.task;
    if (written[step.task].empty()) continue;
    for (std::size_t x = 0; x < devices; ++x) {
      if (x != d) queue[d * devices + x].push_back({here, written[step.task]});
    }
  }
  for (std::size_t o = 0; o < devices; ++o) {
    for (std::size_t d = 0; d < devices; ++d) {
      if (o == d || count_on[o] == 0) continue;
      Transfer t{o, d, last_on[o], steps.size(), {}};
      for (const Pending& p : queue[o * devices + d]) t.elements.add(p.elements);
      if (!t.elements.empty()) out.boundary.push_back(std::move(t));
    }
  }
  return out;
}

void weigh_edges_by_writes(sched::TaskGraph& graph, std::span<const ElementSets> written) {
  if (written.size() != graph.size()) {
    throw internal_error(
        fmt::format("edge weights: writes of {} tasks for a graph of {}", written.size(), graph.size()));
  }
  for (sched::TaskId t = 0; t < graph.size(); ++t) {
    const double bytes = static_cast<double>(written[t].bytes());
    std::vector<sched::TaskId> to;
    for (const sched::Edge& e : graph.successors(t)) to.push_back(e.to);
    for (sched::TaskId v : to) graph.add_edge(t, v, bytes);
  }
}

}  // namespace atssim::plan
