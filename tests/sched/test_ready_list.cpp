#include <catch2/catch.hpp>

#include "sched/list_scheduling.hpp"

using namespace atssim::sched;

namespace {

TaskGraph diamond() {  // 0 → {1, 2} → 3
  TaskGraph g;
  for (const char* n : {"a", "b", "c", "d"}) g.add_task({n, 0, -1, -1});
  g.add_edge(0, 1);
  g.add_edge(0, 2);
  g.add_edge(1, 3);
  g.add_edge(2, 3);
  return g;
}

std::vector<TaskId> drain(ReadyList& list) {
  std::vector<TaskId> order;
  while (!list.empty()) order.push_back(list.pop());
  return order;
}

}  // namespace

TEST_CASE("The ready list takes the highest priority first, equal priorities by id", "[ready_list]") {
  const CompactGraph g(diamond());
  const std::vector<double> rank{10, 4, 7, 1};
  ReadyList list(g, rank);
  CHECK(drain(list) == std::vector<TaskId>{0, 2, 1, 3});
  const std::vector<double> tied{10, 5, 5 + 1e-12, 1};  // equal within 1e-9 ms
  ReadyList tied_list(g, tied);
  CHECK(drain(tied_list) == std::vector<TaskId>{0, 1, 2, 3});
}

TEST_CASE("The ready list never serves a task before its predecessors, whatever the priority", "[ready_list]") {
  const CompactGraph g(diamond());
  const std::vector<double> backwards{1, 5, 2, 9};  // increases along the edges
  ReadyList list(g, backwards);
  CHECK(drain(list) == std::vector<TaskId>{0, 1, 2, 3});
}
