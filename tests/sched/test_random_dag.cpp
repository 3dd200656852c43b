#include <catch2/catch.hpp>

#include "sched/random_dag.hpp"

using namespace atssim::sched;

TEST_CASE("A random DAG is the same for the same seed and differs for another", "[random_dag]") {
  RandomDagOptions o;
  o.tasks = 50;
  const RandomDag a = random_layered_dag(o);
  const RandomDag b = random_layered_dag(o);
  o.seed = 2;
  const RandomDag c = random_layered_dag(o);
  CHECK(a.costs.ms == b.costs.ms);
  CHECK(a.graph.edge_count() == b.graph.edge_count());
  CHECK(a.costs.ms != c.costs.ms);
}

TEST_CASE("A random DAG has the asked size, no cycle, and every task can run somewhere", "[random_dag]") {
  RandomDagOptions o;
  o.tasks = GENERATE(1u, 2u, 37u, 300u);
  o.devices = GENERATE(1u, 3u);
  o.cannot_run_probability = 0.9;
  const RandomDag d = random_layered_dag(o);
  CHECK(d.graph.size() == o.tasks);
  CHECK(d.costs.tasks == o.tasks);
  CHECK(d.costs.devices == o.devices);
  CHECK(d.graph.topological_order().size() == o.tasks);
  for (TaskId t = 0; t < d.graph.size(); ++t) CHECK(min_cost(d.costs, t) < kCannotRun);
}
