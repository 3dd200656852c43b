// Task merging chosen at run time (sched/merged_heft.hpp): the candidates,
// and the choice against makespans worked out by hand.
#include <fmt/format.h>
#include <catch2/catch.hpp>

#include "sched/heft.hpp"
#include "sched/merged_heft.hpp"
#include "sched/task_merging.hpp"

using namespace atssim::sched;

namespace {

constexpr int kStretch = 1, kBend = 2;
constexpr std::size_t kSizes[] = {1, 2, 4, 8};

// A chain of `blocks` colour blocks of one kind, each cut into `parts`
// parts (every part of a block after every part of the block before), each
// part `part_ms` on either of two devices; a hop between the devices costs
// `hop_ms`.
struct CutChain {
  TaskGraph graph;
  CostTable costs;
  DeviceLinks links;
};

CutChain cut_chain(int blocks, int parts, double part_ms, double hop_ms) {
  CutChain c;
  std::vector<TaskId> before;
  std::vector<std::vector<double>> rows;
  for (int b = 0; b < blocks; ++b) {
    std::vector<TaskId> now;
    for (int p = 0; p < parts; ++p) {
      const TaskId id = c.graph.add_task({fmt::format("bend/c{}/p{}", b, p), kBend, 0, b, p});
      for (TaskId from : before) c.graph.add_edge(from, id);
      rows.push_back({part_ms, part_ms});
      now.push_back(id);
    }
    before = now;
  }
  c.costs = CostTable::from_rows(rows);
  c.links = DeviceLinks::unified_memory(2, hop_ms);
  return c;
}

}  // namespace

TEST_CASE("block_groups: the parts of a block, or k consecutive blocks of one kind and iteration", "[merging]") {
  TaskGraph g;
  const TaskId s0 = g.add_task({"it0/stretch/c0", kStretch, 0, 0});
  const TaskId s1 = g.add_task({"it0/stretch/c1", kStretch, 0, 1});
  const TaskId s2 = g.add_task({"it0/stretch/c2", kStretch, 0, 2});
  const TaskId b0p0 = g.add_task({"it0/bend/c0/p0", kBend, 0, 0, 0});
  const TaskId b0p1 = g.add_task({"it0/bend/c0/p1", kBend, 0, 0, 1});
  const TaskId t1 = g.add_task({"it1/stretch/c0", kStretch, 1, 0});
  g.add_task({"predict", 3, -1, -1});
  CHECK(block_groups(g, 1) == std::vector<std::vector<TaskId>>{{b0p0, b0p1}});
  CHECK(block_groups(g, 2) == std::vector<std::vector<TaskId>>{{s0, s1}, {b0p0, b0p1}});
  // The last group of a kind may be shorter; a lone task is no group, and
  // iteration 1's block is not merged with iteration 0's.
  CHECK(block_groups(g, 4) == std::vector<std::vector<TaskId>>{{s0, s1, s2}, {b0p0, b0p1}});
  (void)t1;
}

TEST_CASE("Fig. 3 at run time: the chain of small blocks is merged and moves to the fast device", "[merging]") {
  // As test_task_merging's chain: the input can run only on the CPU (device
  // 1), then 8 blocks of t1 on the GPU (device 0) and t2 on the CPU.
  const auto [t1, t2, tc] = GENERATE(table<double, double, double>({{1.0, 1.5, 1.0}, {0.5, 0.8, 0.9}}));
  TaskGraph g;
  TaskId last = g.add_task({"stretch", kStretch, 0, -1});
  std::vector<std::vector<double>> rows{{kCannotRun, 0.0}};
  for (int b = 0; b < 8; ++b) {
    const TaskId id = g.add_task({fmt::format("bend/c{}", b), kBend, 0, b});
    g.add_edge(last, id);
    rows.push_back({t1, t2});
    last = id;
  }
  const CostTable costs = CostTable::from_rows(rows);
  const DeviceLinks links = DeviceLinks::unified_memory(2, tc);
  const MergedHeft m = schedule_heft_merging(g, costs, links, kSizes);
  CHECK(m.unmerged_makespan_ms == Approx(8 * t2));  // HEFT alone keeps every block on the CPU
  CHECK(m.schedule.makespan_ms == Approx(tc + 8 * t1));
  CHECK(m.blocks_per_group >= 2);  // a lone block stays on the CPU (t2 < tc + t1)
  CHECK(m.schedule.validate(g, costs, links).empty());
  for (TaskId t = 1; t < g.size(); ++t) {
    CHECK(m.schedule.device_of(t) == 0);
    CHECK(m.group[t] >= 0);
  }
  CHECK(m.group[0] == -1);
}

TEST_CASE("Blocks cut into parts run whole, one chain per device, when a hop costs more than a part", "[merging]") {
  // Two independent chains (stretch and bending) of 4 blocks x 2 parts of
  // 1 ms, a hop of 5 ms. Best: each chain whole on its own device, 8 ms.
  // One device takes 16; HEFT alone cuts blocks between the devices and
  // pays hops.
  CutChain c = cut_chain(4, 2, 1.0, 5.0);
  std::vector<TaskId> before;
  std::vector<std::vector<double>> rows(c.graph.size(), {1.0, 1.0});
  for (int b = 0; b < 4; ++b) {
    std::vector<TaskId> now;
    for (int p = 0; p < 2; ++p) {
      const TaskId id = c.graph.add_task({fmt::format("stretch/c{}/p{}", b, p), kStretch, 0, b, p});
      for (TaskId from : before) c.graph.add_edge(from, id);
      rows.push_back({1.0, 1.0});
      now.push_back(id);
    }
    before = now;
  }
  c.costs = CostTable::from_rows(rows);
  const MergedHeft m = schedule_heft_merging(c.graph, c.costs, c.links, kSizes);
  CHECK(m.unmerged_makespan_ms > 8.5);
  CHECK(m.schedule.makespan_ms == Approx(8.0));
  CHECK(m.blocks_per_group >= 1);
  CHECK(m.schedule.validate(c.graph, c.costs, c.links).empty());
  for (TaskId t = 0; t < 8; ++t) CHECK(m.schedule.device_of(t) == m.schedule.device_of(0));
  for (TaskId t = 8; t < 16; ++t) CHECK(m.schedule.device_of(t) != m.schedule.device_of(0));
}

TEST_CASE("No merge where the hop is free: the schedule is HEFT's own", "[merging]") {
  const CutChain c = cut_chain(4, 2, 1.0, 0.0);
  const MergedHeft m = schedule_heft_merging(c.graph, c.costs, c.links, kSizes);
  const Schedule heft = schedule_heft_or_one_device(c.graph, c.costs, c.links);
  CHECK(m.blocks_per_group == 0);
  CHECK(m.groups == 0);
  CHECK(m.schedule.makespan_ms == Approx(4.0));  // both parts of every block at once
  CHECK(m.schedule.makespan_ms == heft.makespan_ms);
  for (int g : m.group) CHECK(g == -1);
}

TEST_CASE("A candidate whose blocks are linked through another kind's task is skipped, not an error", "[merging]") {
  // stretch c0 -> bend c0 -> stretch c1: merging the stretch blocks would
  // make a cycle through the bending block.
  TaskGraph g;
  const TaskId s0 = g.add_task({"stretch/c0", kStretch, 0, 0});
  const TaskId b0 = g.add_task({"bend/c0", kBend, 0, 0});
  const TaskId s1 = g.add_task({"stretch/c1", kStretch, 0, 1});
  g.add_edge(s0, b0);
  g.add_edge(b0, s1);
  const CostTable costs = CostTable::from_rows({{1.0, 2.0}, {1.0, 2.0}, {1.0, 2.0}});
  const DeviceLinks links = DeviceLinks::unified_memory(2, 10.0);
  MergedHeft m;
  REQUIRE_NOTHROW(m = schedule_heft_merging(g, costs, links, kSizes));
  CHECK(m.blocks_per_group == 0);
  CHECK(m.schedule.makespan_ms == Approx(3.0));
}
