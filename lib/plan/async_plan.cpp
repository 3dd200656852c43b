#include "plan/async_plan.hpp"

#include <algorithm>
#include <map>

#include <fmt/format.h>

#include "util/error.hpp"

namespace atssim::plan {

namespace {

// Codes of kernels/async/merge.cl.
constexpr int kCopy = 0, kAveragePositions = 1, kAverageDisplacements = 2;

struct Slot {
  BufferId buffer = -1;
  double busy_until = -1.0;                // predicted start of the last reader of its content
  sched::TaskId content = sched::kNoTask;  // the publication it holds
};

int merge_code(MergeStrategy strategy, const sched::Merge& m, sched::DeviceId main) {
  if (m.start == sched::kNoTask) return m.consumer_device == main ? kAveragePositions : kCopy;
  switch (strategy) {
    case MergeStrategy::average_positions:
      return kAveragePositions;
    case MergeStrategy::average_displacements:
      return kAverageDisplacements;
    case MergeStrategy::main_precedence:
      // Fig. 5(b): a helper that receives the main device's result drops its
      // own data for it; the main device keeps its stream and merges the
      // helpers' displacements from their explicit start points.
      if (m.consumer_device != main && m.producer_device == main) return kCopy;
      return kAverageDisplacements;
  }
  return kAverageDisplacements;
}

}  // namespace

MergeStrategy parse_merge_strategy(const std::string& text) {
  if (text == "average_positions") return MergeStrategy::average_positions;
  if (text == "average_displacements") return MergeStrategy::average_displacements;
  if (text == "main_precedence") return MergeStrategy::main_precedence;
  throw input_error(
      fmt::format("unknown merge strategy '{}'; use average_displacements, average_positions or "
                  "main_precedence",
                  text));
}

std::string to_string(MergeStrategy strategy) {
  switch (strategy) {
    case MergeStrategy::average_positions:
      return "average_positions";
    case MergeStrategy::average_displacements:
      return "average_displacements";
    case MergeStrategy::main_precedence:
      return "main_precedence";
  }
  return "?";
}

AsyncPlan make_async_plan(const SubstepPlan& graph_plan, const sched::Schedule& schedule, const sched::SyncMap& map,
                          MergeStrategy strategy) {
  const auto& graph = graph_plan.graph;
  if (schedule.task_count() != graph.size()) throw internal_error("make_async_plan: the schedule is not of this graph");
  const BufferId x = graph_plan.buffer(BufferRole::positions);
  const std::size_t devices = schedule.devices.size();
  const sched::DeviceId main = map.main_device;
  const int n = graph_plan.particle_count;

  AsyncPlan out;
  SubstepPlan& plan = out.plan;
  plan.program = graph_plan.program;
  plan.buffers = graph_plan.buffers;
  plan.particle_count = n;

  // One copy of the positions per device; the main device's is the plan's.
  std::vector<BufferId> replica(devices, x);
  for (std::size_t d = 0; d < devices; ++d) {
    if (d != main) {
      replica[d] = plan.add_buffer(fmt::format("x@{}", d), BufferRole::replica, graph_plan.buffers[x].initial);
    }
  }
  for (sched::TaskId t = 0; t < graph.size(); ++t) {
    auto launches = graph_plan.launches[t];
    for (auto& l : launches) {
      for (auto& a : l.args) {
        if (a.kind == KernelArg::Kind::buffer && a.buffer == x) a.buffer = replica[schedule.device_of(t)];
      }
      for (auto& w : l.writes) {
        if (w.buffer == x) w.buffer = replica[schedule.device_of(t)];
      }
    }
    plan.add_task(graph.task(t), std::move(launches));
    out.device.push_back(schedule.device_of(t));
  }
  for (sched::TaskId t = 0; t < graph.size(); ++t) {
    for (const auto& e : graph.successors(t)) plan.graph.add_edge(e.from, e.to, e.comm);
  }
  auto next_on_device = [&](sched::TaskId t) -> sched::TaskId {
    const auto& p = schedule.placement[t];
    const auto& slots = schedule.devices[p.device];
    return p.index + 1 < slots.size() ? slots[p.index + 1].task : sched::kNoTask;
  };
  auto previous_on_device = [&](sched::TaskId t) -> sched::TaskId {
    const auto& p = schedule.placement[t];
    return p.index > 0 ? schedule.devices[p.device][p.index - 1].task : sched::kNoTask;
  };

  // Publications: every producer and every start point, in predicted order.
  std::map<sched::TaskId, double> last_use;  // publication -> predicted start of its last reader
  for (const auto& m : map.merges) {
    const double at = schedule.slot(m.consumer).start_ms;
    last_use[m.producer] = std::max(last_use[m.producer], at);
    if (m.start != sched::kNoTask) last_use[m.start] = std::max(last_use[m.start], at);
  }
  std::vector<sched::TaskId> publications;
  for (const auto& [p, when] : last_use) publications.push_back(p);
  std::sort(publications.begin(), publications.end(),
            [&](sched::TaskId a, sched::TaskId b) { return schedule.slot(a).finish_ms < schedule.slot(b).finish_ms; });

  std::vector<Slot> slots;
  std::map<sched::TaskId, std::size_t> slot_of;
  std::map<sched::TaskId, sched::TaskId> publish_task;
  std::map<sched::TaskId, sched::TaskId> previous_content;  // publication -> the one it overwrites
  const std::size_t positions_bytes = graph_plan.buffers[x].initial.size();
  for (sched::TaskId p : publications) {
    const double at = schedule.slot(p).finish_ms;
    std::size_t s = slots.size();
    for (std::size_t i = 0; i < slots.size(); ++i) {
      if (slots[i].busy_until < at && (s == slots.size() || slots[i].busy_until < slots[s].busy_until)) s = i;
    }
    if (s == slots.size()) {
      slots.push_back({plan.add_buffer(fmt::format("snapshot{}", slots.size()), BufferRole::snapshot,
                                       std::vector<std::byte>(positions_bytes)),
                       -1.0, sched::kNoTask});
    }
    const sched::DeviceId d = schedule.device_of(p);
    const sched::Task& source = graph.task(p);
    const sched::TaskId pub =
        plan.add_task(make_task("publish:" + source.name, TaskKind::publish, source.iteration, source.block),
                      {{"async_publish",
                        {0, n},
                        {KernelArg::of_buffer(slots[s].buffer), KernelArg::of_buffer(replica[d])},
                        {WriteSpan::per_element(slots[s].buffer, 16)}}});
    out.device.push_back(d);
    plan.graph.add_edge(p, pub);
    if (const sched::TaskId next = next_on_device(p); next != sched::kNoTask) plan.graph.add_edge(pub, next);
    if (slots[s].content != sched::kNoTask) previous_content[p] = slots[s].content;
    slots[s].content = p;
    slots[s].busy_until = last_use[p];
    slot_of[p] = s;
    publish_task[p] = pub;
  }

  // Merges, chained in map order before their consumer.
  std::map<sched::TaskId, sched::TaskId> last_merge_before;     // consumer -> its latest merge task
  std::map<sched::TaskId, std::vector<sched::TaskId>> readers;  // publication -> merges reading it
  for (const auto& m : map.merges) {
    const BufferId from = slots[slot_of.at(m.producer)].buffer;
    const BufferId start = m.start == sched::kNoTask ? from : slots[slot_of.at(m.start)].buffer;
    const sched::Task& consumer = graph.task(m.consumer);
    const sched::TaskId merge =
        plan.add_task(make_task(fmt::format("merge:{}<-{}", consumer.name, graph.task(m.producer).name),
                                TaskKind::merge, consumer.iteration, consumer.block),
                      {{"async_merge",
                        {0, n},
                        {KernelArg::of_buffer(replica[m.consumer_device]), KernelArg::of_buffer(from),
                         KernelArg::of_buffer(start), KernelArg::of_int(merge_code(strategy, m, main))},
                        {WriteSpan::per_element(replica[m.consumer_device], 16)}}});
    out.device.push_back(m.consumer_device);
    plan.graph.add_edge(publish_task.at(m.producer), merge);
    if (m.start != sched::kNoTask) plan.graph.add_edge(publish_task.at(m.start), merge);
    if (auto it = last_merge_before.find(m.consumer); it != last_merge_before.end()) {
      plan.graph.add_edge(it->second, merge);
    } else if (const sched::TaskId prev = previous_on_device(m.consumer); prev != sched::kNoTask) {
      plan.graph.add_edge(prev, merge);
    }
    last_merge_before[m.consumer] = merge;
    plan.graph.add_edge(merge, m.consumer);
    readers[m.producer].push_back(merge);
    if (m.start != sched::kNoTask) readers[m.start].push_back(merge);
  }
  // A slot's earlier content must have been merged before it is overwritten.
  for (const auto& [p, q] : previous_content) {
    for (sched::TaskId reader : readers[q]) plan.graph.add_edge(reader, publish_task.at(p));
  }
  out.slots = static_cast<int>(slots.size());
  plan.graph.topological_order();  // a cycle here is a bug: fail loudly, naming it
  return out;
}

}  // namespace atssim::plan
