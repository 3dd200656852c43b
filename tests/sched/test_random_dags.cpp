// Property tests over seeded random DAGs, and HEFT / CPOP / PEFT against the
// exhaustive optimum on tiny ones.
#include <fmt/format.h>
#include <catch2/catch.hpp>

#include <cstdio>

#include "exhaustive_search.hpp"
#include "sched/cpop.hpp"
#include "sched/heft.hpp"
#include "sched/lower_bound.hpp"
#include "sched/peft.hpp"
#include "sched/random_dag.hpp"

using namespace atssim::sched;

namespace {

// Deterministic variety: size, devices, shape, communication-to-computation
// ratio, unusable devices and busy devices all vary with the seed.
struct Case {
  RandomDag dag;
  DeviceLinks links;
  std::vector<double> ready;
};

Case random_case(std::uint64_t seed, std::size_t min_tasks, std::size_t max_tasks) {
  std::uint64_t x = seed * 0x9E3779B97F4A7C15ull + 1;
  auto next = [&](std::uint64_t n) {
    x ^= x >> 31;
    x *= 0xBF58476D1CE4E5B9ull;
    x ^= x >> 29;
    return x % n;
  };
  RandomDagOptions o;
  o.seed = seed;
  o.tasks = min_tasks + next(max_tasks - min_tasks + 1);
  o.devices = 2 + next(3);
  o.layer_width = 1 + next(6);
  o.max_inputs = 1 + next(3);
  o.min_cost_ms = 0.5;
  o.max_cost_ms = 1.0 + static_cast<double>(next(20));
  o.max_weight = static_cast<double>(next(4)) * 5.0;  // 0 … 15: from free to costly transfers
  o.cannot_run_probability = next(3) == 0 ? 0.25 : 0.0;
  Case c{random_layered_dag(o), DeviceLinks::weighted(o.devices), {}};
  switch (next(4)) {
    case 0:
      c.links = DeviceLinks::unified_memory(o.devices, 0.2 * static_cast<double>(next(10)));
      break;
    case 1:
      c.links = DeviceLinks::weighted(o.devices, 0.5, 0.5);
      break;
    default:
      break;
  }
  if (next(4) == 0) {
    for (std::size_t d = 0; d < o.devices; ++d) c.ready.push_back(static_cast<double>(next(10)));
  }
  return c;
}

Schedule run(int algorithm, const Case& c) {
  ListOptions list;
  list.device_ready_ms = c.ready;
  switch (algorithm) {
    case 0: {
      HeftOptions h;
      h.device_ready_ms = c.ready;
      return schedule_heft(c.dag.graph, c.dag.costs, c.links, h);
    }
    case 1:
      return schedule_cpop(c.dag.graph, c.dag.costs, c.links, list);
    default:
      return schedule_peft(c.dag.graph, c.dag.costs, c.links, list);
  }
}

constexpr const char* kNames[] = {"HEFT", "CPOP", "PEFT"};

}  // namespace

TEST_CASE(
    "HEFT, CPOP and PEFT schedules of 1,000 random DAGs validate and respect the lower "
    "bounds",
    "[random]") {
  for (std::uint64_t seed = 1; seed <= 1000; ++seed) {
    const Case c = random_case(seed, 2, 200);
    const double ready_min = c.ready.empty() ? 0.0 : *std::min_element(c.ready.begin(), c.ready.end());
    const double bound = makespan_lower_bound(c.dag.graph, c.dag.costs);
    for (int a = 0; a < 3; ++a) {
      const Schedule s = run(a, c);
      const auto problems = s.validate(c.dag.graph, c.dag.costs, c.links);
      if (!problems.empty() || s.makespan_ms < bound + ready_min - 1e-9) {
        FAIL(fmt::format("{} on seed {} ({} tasks, {} devices): {} ; makespan {} < bound {}", kNames[a], seed,
                         c.dag.graph.size(), c.dag.costs.devices, problems.empty() ? "valid" : problems.front(),
                         s.makespan_ms, bound + ready_min));
      }
      // Waits can be derived for every valid schedule.
      const auto waits = s.cross_device_waits(c.dag.graph);
      for (const Wait& w : waits) {
        if (w.producer_device == w.consumer_device) FAIL("a wait on the task's own queue");
      }
    }
  }
  SUCCEED();
}

TEST_CASE("On 1,000 random DAGs of at most 8 tasks no heuristic beats the exhaustive optimum", "[random][exhaustive]") {
  int reached[3] = {0, 0, 0};
  double ratio_sum[3] = {0, 0, 0};
  const int cases = 1000;
  for (std::uint64_t seed = 1; seed <= cases; ++seed) {
    const Case c = random_case(seed + 100000, 2, 8);
    double makespan[3];
    for (int a = 0; a < 3; ++a) makespan[a] = run(a, c).makespan_ms;
    // The search starts unbounded: no heuristic's makespan enters it.
    const double optimum = test::optimal_makespan(c.dag.graph, c.dag.costs, c.links, c.ready);
    const double tol = 1e-9 * std::max(1.0, optimum);
    // Every heuristic schedule is one the search enumerates (left-shifted), so
    // the optimum is at most the best of them.
    const double best_heuristic = *std::min_element(makespan, makespan + 3);
    if (optimum > best_heuristic + tol) {
      FAIL(fmt::format("seed {}: the exhaustive optimum {} is above a heuristic's makespan {}", seed, optimum,
                       best_heuristic));
    }
    for (int a = 0; a < 3; ++a) {
      if (makespan[a] < optimum - tol) {
        FAIL(fmt::format("{} on seed {} has makespan {} below the optimum {}", kNames[a], seed, makespan[a], optimum));
      }
      reached[a] += makespan[a] <= optimum + tol;
      ratio_sum[a] += makespan[a] / optimum;
    }
  }
  for (int a = 0; a < 3; ++a) {
    std::printf(
        "%s reached the exhaustive optimum on %d of %d DAGs (<= 8 tasks); mean "
        "makespan / optimum %.4f\n",
        kNames[a], reached[a], cases, ratio_sum[a] / cases);
  }
  CHECK(reached[0] > 0);
}

TEST_CASE("The exhaustive search finds hand-computed optima", "[exhaustive]") {
  // Two independent tasks, two devices: each on its own device.
  TaskGraph g;
  g.add_task({"a", 0, -1, -1});
  g.add_task({"b", 0, -1, -1});
  const auto costs = CostTable::from_rows({{3, 5}, {4, 6}});
  const auto links = DeviceLinks::weighted(2);
  CHECK(test::optimal_makespan(g, costs, links) == 5.0);  // a@1 (5) ‖ b@0 (4)
  // a → b with a costly transfer: both on device 0.
  g.add_edge(0, 1, 10);
  CHECK(test::optimal_makespan(g, costs, links) == 7.0);
  // Device 0 busy until 20: everything on device 1.
  const std::vector<double> ready{20, 0};
  CHECK(test::optimal_makespan(g, costs, links, ready) == 11.0);
}

namespace {

// Plain enumeration: every order of appending ready tasks to every device,
// no start-order restriction, no bound. Slow; a check on the search above.
double brute_force(const TaskGraph& g, const CostTable& costs, const DeviceLinks& links, std::uint32_t placed,
                   std::vector<double>& free, std::vector<double>& finish, std::vector<DeviceId>& device,
                   double makespan) {
  const std::size_t n = g.size();
  if (placed == (1u << n) - 1) return makespan;
  double best = kCannotRun;
  for (TaskId t = 0; t < n; ++t) {
    if (placed >> t & 1) continue;
    bool ready = true;
    for (const Edge& e : g.predecessors(t)) ready = ready && (placed >> e.from & 1);
    if (!ready) continue;
    for (DeviceId d = 0; d < costs.devices; ++d) {
      if (!costs.can_run(t, d)) continue;
      double start = free[d];
      for (const Edge& e : g.predecessors(t)) {
        start = std::max(start, finish[e.from] + links.comm_ms(e.comm, device[e.from], d));
      }
      const double saved = free[d];
      free[d] = finish[t] = start + costs.at(t, d);
      device[t] = d;
      best = std::min(
          best, brute_force(g, costs, links, placed | 1u << t, free, finish, device, std::max(makespan, finish[t])));
      free[d] = saved;
    }
  }
  return best;
}

}  // namespace

TEST_CASE("The exhaustive search agrees with plain enumeration on 200 DAGs of at most 5 tasks", "[exhaustive]") {
  for (std::uint64_t seed = 1; seed <= 200; ++seed) {
    const Case c = random_case(seed + 200000, 2, 5);
    std::vector<double> free = c.ready;
    if (free.empty()) free.assign(c.dag.costs.devices, 0.0);
    std::vector<double> finish(c.dag.graph.size());
    std::vector<DeviceId> device(c.dag.graph.size());
    const double plain = brute_force(c.dag.graph, c.dag.costs, c.links, 0, free, finish, device, 0.0);
    const double searched = test::optimal_makespan(c.dag.graph, c.dag.costs, c.links, c.ready);
    CAPTURE(seed);
    REQUIRE(searched == Approx(plain).epsilon(1e-12));
  }
}
