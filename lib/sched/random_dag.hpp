#pragma once
// Seeded random layered DAGs for property tests and benchmarks. The same
// seed gives the same DAG on every platform (own uniform mapping of
// std::mt19937_64, whose output the standard fixes).
#include <cstddef>
#include <cstdint>

#include "sched/cost_table.hpp"
#include "sched/task_graph.hpp"

namespace atssim::sched {

struct RandomDagOptions {
  std::size_t tasks = 100;
  std::size_t devices = 2;
  std::size_t layer_width = 0;     // mean tasks per layer; 0 = about sqrt(tasks)
  std::size_t max_inputs = 3;      // a task past the first layer reads 1..max_inputs earlier tasks
  double local_input_share = 0.7;  // share of inputs taken from the previous layer
  double min_cost_ms = 1.0;
  double max_cost_ms = 10.0;
  double min_weight = 0.0;
  double max_weight = 10.0;
  // Chance that a (task, device) entry is inf; one device per task always stays finite.
  double cannot_run_probability = 0.0;
  std::uint64_t seed = 1;
};

struct RandomDag {
  TaskGraph graph;
  CostTable costs;
};

RandomDag random_layered_dag(const RandomDagOptions& options);

}  // namespace atssim::sched
