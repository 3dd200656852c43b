// Task merging (paper §4.1.1, Fig. 3).
#include <fmt/format.h>
#include <catch2/catch.hpp>

#include "sched/heft.hpp"
#include "sched/task_merging.hpp"
#include "util/error.hpp"

using namespace atssim::sched;

namespace {

constexpr int kStretch = 1, kBend = 2;  // kind labels: the scheduler only compares them

constexpr DeviceId kGpu = 0;
constexpr DeviceId kCpu = 1;

// Fig. 3: the chain's input lives on the CPU (the task before it can only
// run there), then 8 bending blocks in Gauss-Seidel order, each t1 on the
// GPU and t2 on the CPU; a CPU↔GPU switch costs tc (unified memory).
struct BendingChain {
  TaskGraph graph;
  CostTable costs;
  DeviceLinks links;
  std::vector<TaskId> blocks;
};

BendingChain bending_chain(double t1, double t2, double tc) {
  BendingChain c;
  const TaskId input = c.graph.add_task({"stretch", kStretch, 0, -1});
  std::vector<std::vector<double>> rows{{kCannotRun, 0.0}};
  TaskId last = input;
  for (int b = 0; b < 8; ++b) {
    const TaskId id = c.graph.add_task({fmt::format("bend/c{}", b), kBend, 0, b});
    c.graph.add_edge(last, id);
    rows.push_back({t1, t2});
    c.blocks.push_back(id);
    last = id;
  }
  c.costs = CostTable::from_rows(rows);
  c.links = DeviceLinks::unified_memory(2, tc);
  return c;
}

}  // namespace

TEST_CASE("Fig. 3: merging bending blocks by 4 gives tc + 8·t1 instead of 8·t2", "[merging]") {
  const auto [t1, t2, tc] =
      GENERATE(table<double, double, double>({{1.0, 1.5, 1.0}, {2.0, 2.5, 1.5}, {0.5, 0.8, 0.9}, {0.25, 0.3, 0.15}}));
  // The paper's conditions: the CPU keeps a lone block, a block of 4 moves.
  REQUIRE(t1 < t2);
  REQUIRE(t2 < tc + t1);
  REQUIRE(4 * t2 > tc + 4 * t1);
  const BendingChain c = bending_chain(t1, t2, tc);

  const Schedule plain = schedule_heft(c.graph, c.costs, c.links);
  CHECK(plain.makespan_ms == Approx(8 * t2));
  for (TaskId b : c.blocks) CHECK(plain.device_of(b) == kCpu);

  const auto groups = consecutive_groups(c.blocks, 4);
  const MergedGraph merged = merge_tasks(c.graph, c.costs, groups);
  const Schedule fused = schedule_heft(merged.graph, merged.costs, c.links);
  CHECK(fused.makespan_ms == Approx(tc + 8 * t1));
  for (TaskId b : c.blocks) CHECK(fused.device_of(merged.merged_id[b]) == kGpu);
}

TEST_CASE("A merged schedule expands to a valid schedule of the original blocks", "[merging]") {
  const BendingChain c = bending_chain(1.0, 1.5, 1.0);
  const MergedGraph merged = merge_tasks(c.graph, c.costs, consecutive_groups(c.blocks, 4));
  const Schedule fused = schedule_heft(merged.graph, merged.costs, c.links);
  const Schedule expanded = expand_merged_schedule(fused, merged, c.costs);
  CHECK(expanded.validate(c.graph, c.costs, c.links).empty());
  CHECK(expanded.makespan_ms == Approx(fused.makespan_ms));
  CHECK(expanded.devices[kGpu].size() == 8);
}

TEST_CASE("The smallest profitable merge is the first k with k·t2 > tc + k·t1", "[merging]") {
  const auto [t1, t2, tc, k] = GENERATE(table<double, double, double, std::size_t>(
      {{1.0, 1.5, 1.0, 3}, {1.0, 1.5, 1.5, 4}, {1.0, 3.0, 1.0, 1}, {2.0, 1.0, 1.0, 0}}));
  CHECK(profitable_merge_size(t1, t2, tc) == k);
}

TEST_CASE("A merged task costs the sum of its members and keeps outside edges", "[merging]") {
  // a → b → c → d, a → c (weight 7), merge {b, c}.
  TaskGraph g;
  for (const char* n : {"a", "b", "c", "d"}) g.add_task({n, kBend, 1, -1});
  g.add_edge(0, 1, 2);
  g.add_edge(1, 2, 3);
  g.add_edge(2, 3, 4);
  g.add_edge(0, 2, 7);
  const auto costs = CostTable::from_rows({{1, 2}, {3, 4}, {5, kCannotRun}, {7, 8}});
  const std::vector<std::vector<TaskId>> groups{{2, 1}};
  const MergedGraph m = merge_tasks(g, costs, groups);
  REQUIRE(m.graph.size() == 3);
  const TaskId bc = m.merged_id[1];
  CHECK(m.merged_id[2] == bc);
  CHECK(m.graph.task(bc).name == "b+c");
  CHECK(m.graph.task(bc).kind == kBend);
  CHECK(m.members[bc] == std::vector<TaskId>{1, 2});  // run order, not the order given
  CHECK(m.costs.at(bc, 0) == 8.0);
  CHECK_FALSE(m.costs.can_run(bc, 1));
  REQUIRE(m.graph.predecessors(bc).size() == 1);
  CHECK(m.graph.predecessors(bc)[0].comm == 7.0);  // a→b (2) and a→c (7): the larger
  REQUIRE(m.graph.successors(bc).size() == 1);
  CHECK(m.graph.successors(bc)[0].comm == 4.0);
}

TEST_CASE("Merging tasks linked through an outside task is an error naming the cycle", "[merging]") {
  TaskGraph g;
  for (const char* n : {"a", "b", "c"}) g.add_task({n, 0, -1, -1});
  g.add_edge(0, 1);
  g.add_edge(1, 2);
  const CostTable costs(3, 2, 1.0);
  const std::vector<std::vector<TaskId>> groups{{0, 2}};
  CHECK_THROWS_WITH(merge_tasks(g, costs, groups),
                    Catch::Contains("cycle") && Catch::Contains("a+c") && Catch::Contains("b"));
}

TEST_CASE("A task in two merge groups is an error", "[merging]") {
  TaskGraph g;
  for (const char* n : {"a", "b", "c"}) g.add_task({n, 0, -1, -1});
  const CostTable costs(3, 2, 1.0);
  const std::vector<std::vector<TaskId>> groups{{0, 1}, {1, 2}};
  CHECK_THROWS_WITH(merge_tasks(g, costs, groups), Catch::Contains("'b' is in more than one"));
}
