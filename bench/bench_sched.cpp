// Scheduling time of HEFT, CPOP and PEFT on seeded layered random DAGs on 2
// devices (DESIGN.md: "Scheduling must cost < 0.1 ms per substep DAG").
// Prints a Markdown table of the median wall time per call; each call
// includes input checks, topological order, ranks and placement.
//
//   bench_sched [--sizes 300,3000,30000,100000] [--seconds 1.0]
#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <string>
#include <vector>

#include "sched/cpop.hpp"
#include "sched/heft.hpp"
#include "sched/peft.hpp"
#include "sched/random_dag.hpp"

using namespace atssim::sched;

namespace {

using Clock = std::chrono::steady_clock;

// Median of repeated calls; repeats until `budget_s` is spent (at least 5,
// at most 100,000 calls).
template <class F>
double median_ms(F&& call, double budget_s) {
  std::vector<double> samples;
  const auto begin = Clock::now();
  double makespan_sink = 0.0;
  while (samples.size() < 5 ||
         (std::chrono::duration<double>(Clock::now() - begin).count() < budget_s && samples.size() < 100000)) {
    const auto t0 = Clock::now();
    makespan_sink += call().makespan_ms;
    samples.push_back(std::chrono::duration<double, std::milli>(Clock::now() - t0).count());
  }
  if (makespan_sink < 0) std::puts("");  // keep the calls observable
  std::nth_element(samples.begin(), samples.begin() + samples.size() / 2, samples.end());
  return samples[samples.size() / 2];
}

std::vector<std::size_t> parse_sizes(const char* text) {
  std::vector<std::size_t> sizes;
  std::string s(text);
  std::size_t pos = 0;
  while (pos < s.size()) {
    const std::size_t comma = s.find(',', pos);
    sizes.push_back(std::stoul(s.substr(pos, comma - pos)));
    pos = comma == std::string::npos ? s.size() : comma + 1;
  }
  return sizes;
}

}  // namespace

int main(int argc, char** argv) {
  std::vector<std::size_t> sizes{300, 3000, 30000, 100000};
  double seconds = 1.0;
  for (int i = 1; i + 1 < argc; i += 2) {
    if (std::strcmp(argv[i], "--sizes") == 0) {
      sizes = parse_sizes(argv[i + 1]);
    } else if (std::strcmp(argv[i], "--seconds") == 0) {
      seconds = std::atof(argv[i + 1]);
    } else {
      std::fprintf(stderr, "usage: bench_sched [--sizes N,N,...] [--seconds S]\n");
      return 2;
    }
  }
  std::printf("| tasks | edges | HEFT ms | CPOP ms | PEFT ms | HEFT makespan / bound |\n");
  std::printf("|---:|---:|---:|---:|---:|---:|\n");
  for (std::size_t n : sizes) {
    RandomDagOptions o;
    o.tasks = n;
    o.devices = 2;
    o.seed = 42;
    const RandomDag dag = random_layered_dag(o);
    const auto links = DeviceLinks::unified_memory(2, 0.2);
    const double heft = median_ms([&] { return schedule_heft(dag.graph, dag.costs, links); }, seconds);
    const double cpop = median_ms([&] { return schedule_cpop(dag.graph, dag.costs, links); }, seconds);
    const double peft = median_ms([&] { return schedule_peft(dag.graph, dag.costs, links); }, seconds);
    const Schedule s = schedule_heft(dag.graph, dag.costs, links);
    double work = 0.0;
    for (TaskId t = 0; t < n; ++t) work += min_cost(dag.costs, t);
    std::printf("| %zu | %zu | %.4f | %.4f | %.4f | %.3f |\n", n, dag.graph.edge_count(), heft, cpop, peft,
                s.makespan_ms / (work / 2.0));
    std::fflush(stdout);
  }
  return 0;
}
