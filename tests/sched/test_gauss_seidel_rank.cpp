// Gauss-Seidel rank_u (paper §4.1.2, Fig. 9).
#include <fmt/format.h>
#include <catch2/catch.hpp>

#include "sched/gauss_seidel_rank.hpp"
#include "sched/heft.hpp"
#include "sched/rank.hpp"

using namespace atssim::sched;

namespace {

constexpr int kStretch = 1;  // kind labels: the scheduler only compares them

// 4 iterations × 5 color blocks of one constraint kind. Within an iteration
// the blocks run in Gauss-Seidel order (block b+1 reads block b); block b of
// iteration k+1 reads block b of iteration k. Nothing else orders the
// iterations, so an asynchronous scheduler may start iteration k+1 early.
// Two devices: block costs differ per block, unified memory, 0.2 ms hops.
struct Grid {
  TaskGraph graph;
  CostTable costs;
  DeviceLinks links = DeviceLinks::unified_memory(2, 0.2);
  std::vector<TaskId> gs_order;
};

Grid grid() {
  Grid g;
  constexpr int kIterations = 4;
  constexpr int kBlocks = 5;
  const double gpu[kBlocks] = {1.0, 0.6, 0.9, 0.4, 0.7};
  std::vector<std::vector<double>> rows;
  for (int k = 0; k < kIterations; ++k) {
    for (int b = 0; b < kBlocks; ++b) {
      const TaskId id = g.graph.add_task({fmt::format("it{}/stretch/c{}", k, b), kStretch, k, b});
      if (b > 0) g.graph.add_edge(id - 1, id);
      if (k > 0) g.graph.add_edge(id - kBlocks, id);
      rows.push_back({gpu[b], 1.7 * gpu[b]});
    }
  }
  g.costs = CostTable::from_rows(rows);
  g.gs_order = gauss_seidel_order(g.graph, kStretch);
  return g;
}

// Position of each task in the order the scheduler took it.
std::vector<std::size_t> taken_at(const Schedule& s) {
  std::vector<std::size_t> at(s.task_count());
  for (std::size_t i = 0; i < s.scheduling_order.size(); ++i) at[s.scheduling_order[i]] = i;
  return at;
}

}  // namespace

TEST_CASE("gauss_seidel_order sorts a kind's tasks by iteration, then block", "[gauss_seidel]") {
  const Grid g = grid();
  REQUIRE(g.gs_order.size() == 20);
  for (std::size_t i = 0; i < 20; ++i) CHECK(g.gs_order[i] == i);
}

TEST_CASE("Plain rank_u lets a later iteration overtake the Gauss-Seidel order", "[gauss_seidel]") {
  const Grid g = grid();
  const Schedule s = schedule_heft(g.graph, g.costs, g.links);
  const auto at = taken_at(s);
  bool out_of_order = false;
  for (std::size_t i = 1; i < g.gs_order.size(); ++i) {
    out_of_order = out_of_order || at[g.gs_order[i]] < at[g.gs_order[i - 1]];
  }
  CHECK(out_of_order);
}

TEST_CASE("Gauss-Seidel ranks strictly decrease along the order and along every edge", "[gauss_seidel]") {
  const Grid g = grid();
  const auto rank = gauss_seidel_rank(g.graph, g.costs, g.links, g.gs_order);
  for (std::size_t i = 1; i < g.gs_order.size(); ++i) {
    CHECK(rank[g.gs_order[i]] < rank[g.gs_order[i - 1]]);
  }
  for (TaskId t = 0; t < g.graph.size(); ++t) {
    for (const Edge& e : g.graph.successors(t)) CHECK(rank[e.to] < rank[t]);
  }
}

TEST_CASE("Gauss-Seidel rank keeps the order of a 4-iteration × 5-block chain on two devices", "[gauss_seidel]") {
  const Grid g = grid();
  HeftOptions options;
  options.priority = gauss_seidel_rank(g.graph, g.costs, g.links, g.gs_order);
  const Schedule s = schedule_heft(g.graph, g.costs, g.links, options);
  CHECK(s.validate(g.graph, g.costs, g.links).empty());
  CHECK(s.scheduling_order == g.gs_order);
  // Each device's in-order queue runs its blocks in Gauss-Seidel order.
  for (const auto& slots : s.devices) {
    for (std::size_t i = 1; i < slots.size(); ++i) CHECK(slots[i - 1].task < slots[i].task);
  }
  CHECK_FALSE(s.devices[0].empty());
  CHECK_FALSE(s.devices[1].empty());
}

TEST_CASE("A Gauss-Seidel order that contradicts the graph is an error naming the cycle", "[gauss_seidel]") {
  const Grid g = grid();
  std::vector<TaskId> backwards(g.gs_order.rbegin(), g.gs_order.rend());
  CHECK_THROWS_WITH(gauss_seidel_rank(g.graph, g.costs, g.links, backwards),
                    Catch::Contains("contradicts") && Catch::Contains("it0/stretch/c0"));
}
