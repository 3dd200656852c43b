// Cost of the per-frame surface record (solver/contact/surface_contacts:
// pairs within the contact thickness, the deepest, and the edge-triangle
// crossing check) on the folded, crumpled sheet of the broad-phase
// benchmark (broad_phase/crumpled_sheet.hpp), on 1 and on N TBB threads.
//
//   bench_surface_contacts [--sizes 64,128,256] [--threads 1,2] [--rounds 5] [--default-memory]
//
// Prints per size and thread count the median wall ms of one measure() call
// (the float state as the run hands it over, on a thread started for the
// call as in the run), the median process CPU ms (what it costs on a
// loaded machine, all threads summed) and what it found.
#include <algorithm>
#include <chrono>
#include <ctime>
#include <future>
#include <string>
#include <vector>

#include <fmt/format.h>
#include <tbb/task_arena.h>
#include <CLI/CLI.hpp>

#include "broad_phase/crumpled_sheet.hpp"
#include "solver/contact/surface_contacts.hpp"
#include "util/freed_memory.hpp"

using namespace atssim;
using Clock = std::chrono::steady_clock;

namespace {

double median(std::vector<double> v) {
  std::nth_element(v.begin(), v.begin() + v.size() / 2, v.end());
  return v[v.size() / 2];
}

}  // namespace

int main(int argc, char** argv) {
  CLI::App cli{"Cost of the per-frame surface contact record"};
  std::vector<int> sizes{64, 128, 256}, threads{1, 2};
  int rounds = 5;
  cli.add_option("--sizes", sizes, "grid vertices per side")->delimiter(',');
  cli.add_option("--threads", threads, "TBB thread counts")->delimiter(',');
  cli.add_option("--rounds", rounds, "timed calls per case (median)")->check(CLI::PositiveNumber);
  bool default_memory = false;
  cli.add_flag("--default-memory", default_memory,
               "glibc's default handling of freed memory, rather than kept as atssim run keeps it "
               "(util/freed_memory.hpp: the setting holds for the process and every thread it starts, so "
               "compare two runs)");
  CLI11_PARSE(cli, argc, argv);
  fmt::print("{:>8} {:>7} {:>9} {:>9} {:>9} {:>9} {:>11} {:>8}\n", "vertices", "threads", "wall_ms", "cpu_ms", "pairs",
             "crossings", "depth_m", "memory");
  const bool kept = !default_memory;
  if (kept && !util::keep_freed_memory()) fmt::print("(the C library refused to keep freed memory)\n");
  for (int n : sizes) {
    const model::Model m = bench::crumpled_sheet(n);
    std::vector<float> xyz;
    for (const auto& p : m.particles.position) {
      for (int k = 0; k < 3; ++k) xyz.push_back(static_cast<float>(p[k]));
    }
    const solver::SurfaceContactCheck check(m.contact_surface->triangles, m.contact_surface->thickness);
    for (int t : threads) {
      tbb::task_arena arena(t);
      std::vector<double> ms, cpu;
      solver::SurfaceContacts found;
      for (int r = 0; r < rounds + 1; ++r) {
        const auto start = Clock::now();
        const std::clock_t cpu_start = std::clock();
        // On a thread of its own, started for the call, as `atssim run`
        // measures each frame's record (app/simulation.cpp
        // SurfaceMeasurement): that thread's allocations are what the
        // memory setting has to keep.
        std::async(std::launch::async, [&] { arena.execute([&] { found = check.measure(xyz); }); }).get();
        if (r == 0) continue;  // warm-up
        ms.push_back(std::chrono::duration<double, std::milli>(Clock::now() - start).count());
        cpu.push_back(1000.0 * double(std::clock() - cpu_start) / CLOCKS_PER_SEC);
      }
      fmt::print("{:>8} {:>7} {:>9.1f} {:>9.1f} {:>9} {:>9} {:>11.3g} {:>8}\n", n * n, t, median(ms), median(cpu),
                 found.pairs(), found.crossings, found.max_penetration, kept ? "kept" : "default");
    }
  }
  return 0;
}
