#include "sched/random_dag.hpp"

#include <algorithm>
#include <cmath>
#include <random>
#include <string>

#include <fmt/format.h>

namespace atssim::sched {

namespace {

class Random {
 public:
  explicit Random(std::uint64_t seed) : engine_(seed) {}
  double uniform(double lo, double hi) { return lo + (hi - lo) * (static_cast<double>(engine_() >> 11) * 0x1.0p-53); }
  // Uniform in [0, n).
  std::size_t below(std::size_t n) { return static_cast<std::size_t>(uniform(0.0, static_cast<double>(n))); }

 private:
  std::mt19937_64 engine_;
};

}  // namespace

RandomDag random_layered_dag(const RandomDagOptions& o) {
  Random rng(o.seed);
  RandomDag dag;
  const std::size_t width =
      o.layer_width > 0 ? o.layer_width : std::max<std::size_t>(1, static_cast<std::size_t>(std::sqrt(o.tasks)));
  std::size_t layer_begin = 0;  // first task of the current layer
  std::size_t prev_begin = 0;   // first task of the previous layer
  std::size_t layer_left = 0;
  int layer = -1;
  for (std::size_t i = 0; i < o.tasks; ++i) {
    if (layer_left == 0) {
      prev_begin = layer_begin;
      layer_begin = i;
      layer_left = 1 + rng.below(2 * width - 1);
      ++layer;
    }
    --layer_left;
    const TaskId id = dag.graph.add_task({fmt::format("t{}", i), 0, layer, -1});
    if (layer == 0) continue;
    const std::size_t inputs = 1 + rng.below(std::max<std::size_t>(1, o.max_inputs));
    for (std::size_t k = 0; k < inputs; ++k) {
      const bool local = rng.uniform(0.0, 1.0) < o.local_input_share;
      const std::size_t lo = local ? prev_begin : 0;
      const auto from = static_cast<TaskId>(lo + rng.below(layer_begin - lo));
      dag.graph.add_edge(from, id, rng.uniform(o.min_weight, o.max_weight));
    }
  }
  dag.costs = CostTable(o.tasks, o.devices);
  for (TaskId t = 0; t < o.tasks; ++t) {
    const DeviceId always = static_cast<DeviceId>(rng.below(o.devices));
    for (DeviceId d = 0; d < o.devices; ++d) {
      const double cost = rng.uniform(o.min_cost_ms, o.max_cost_ms);
      const bool cannot = d != always && rng.uniform(0.0, 1.0) < o.cannot_run_probability;
      dag.costs.at(t, d) = cannot ? kCannotRun : cost;
    }
  }
  return dag;
}

}  // namespace atssim::sched
