#include <fmt/format.h>
#include <catch2/catch.hpp>

#include "sched/task_graph.hpp"
#include "util/error.hpp"

using namespace atssim::sched;

namespace {

constexpr int kPredict = 1, kStretch = 2, kBend = 3, kUpdate = 4;  // kind labels

TaskGraph chain(int n) {
  TaskGraph g;
  for (int i = 0; i < n; ++i) g.add_task({fmt::format("t{}", i), 0, -1, -1});
  for (int i = 1; i < n; ++i) g.add_edge(i - 1, i, 1.0);
  return g;
}

}  // namespace

TEST_CASE("A cycle is an error that names the tasks on it", "[task_graph]") {
  TaskGraph g;
  const TaskId a = g.add_task({"predict", kPredict, -1, -1});
  const TaskId b = g.add_task({"it1/stretch/c0", kStretch, 1, 0});
  const TaskId c = g.add_task({"it1/bend/c0", kBend, 1, 0});
  const TaskId d = g.add_task({"update_velocity", kUpdate, -1, -1});
  g.add_edge(a, b);
  g.add_edge(b, c);
  g.add_edge(c, b);
  g.add_edge(c, d);
  CHECK_THROWS_AS(g.topological_order(), atssim::Error);
  CHECK_THROWS_WITH(g.topological_order(), Catch::Contains("it1/stretch/c0 -> it1/bend/c0 -> it1/stretch/c0") ||
                                               Catch::Contains("it1/bend/c0 -> it1/stretch/c0 -> it1/bend/c0"));
  CHECK_THROWS_WITH(g.topological_order(), !Catch::Contains("predict"));
}

TEST_CASE("Topological order breaks ties by the smallest id", "[task_graph]") {
  TaskGraph g;
  for (int i = 0; i < 4; ++i) g.add_task({fmt::format("t{}", i), 0, -1, -1});
  g.add_edge(3, 1);
  g.add_edge(2, 1);
  CHECK(g.topological_order() == std::vector<TaskId>{0, 2, 3, 1});
}

TEST_CASE("A repeated edge keeps the larger weight on both ends", "[task_graph]") {
  TaskGraph g = chain(2);
  g.add_edge(0, 1, 5.0);
  g.add_edge(0, 1, 2.0);
  REQUIRE(g.successors(0).size() == 1);
  CHECK(g.successors(0)[0].comm == 5.0);
  CHECK(g.predecessors(1)[0].comm == 5.0);
  CHECK(g.edge_count() == 1);
}

TEST_CASE("An edge to a task that does not exist or to itself is an error", "[task_graph]") {
  TaskGraph g = chain(2);
  CHECK_THROWS_WITH(g.add_edge(0, 7), Catch::Contains("does not exist"));
  CHECK_THROWS_WITH(g.add_edge(1, 1), Catch::Contains("'t1' cannot depend on itself"));
}
