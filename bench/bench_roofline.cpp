// The machine's limits for the roofline of docs/benchmarks.md: the stream
// triad a[i] = b[i] + s c[i] (McCalpin's STREAM kernel, 12 bytes per
// element: two floats read, one written; write-allocate traffic not
// counted) over arrays far past the last-level cache (memory) and over
// arrays that fit in it (cache), and the peak of fused multiply-adds on
// 8-float vectors (10 independent chains per thread, so that the FMA
// latency is hidden), each on 1 and on N threads (tbb::parallel_for in an
// arena). The best of R repetitions counts (STREAM's convention).
//
//   bench_roofline [--threads 2] [--repeat 5] [--memory-mib 768] [--cache-mib 12]
//
// Prints one line of JSON: triad GB/s (memory and cache, per thread count)
// and GFLOP/s (an FMA is 2 flops), per thread count.
#include <algorithm>
#include <chrono>
#include <cstdio>
#include <string>
#include <vector>

#include <fmt/format.h>
#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>
#include <tbb/task_arena.h>
#include <CLI/CLI.hpp>

namespace {

using Clock = std::chrono::steady_clock;

double seconds_since(Clock::time_point t0) { return std::chrono::duration<double>(Clock::now() - t0).count(); }

// Best GB/s of `repeat` triads over n floats per array, on `threads` threads.
double triad_gbs(std::size_t n, int threads, int repeat) {
  std::vector<float> a(n, 0.0f), b(n, 1.0f), c(n, 2.0f);
  tbb::task_arena arena(threads);
  double best = 0.0;
  const int sweeps = std::max<int>(1, static_cast<int>((std::size_t{64} << 20) / n));  // >= 64M elements per timing
  for (int r = 0; r < repeat + 1; ++r) {  // the first is a warm-up (first touch, workers)
    const auto t0 = Clock::now();
    arena.execute([&] {
      for (int s = 0; s < sweeps; ++s) {
        const float k = 0.5f + static_cast<float>(s & 1);
        tbb::parallel_for(tbb::blocked_range<std::size_t>(0, n, 1 << 14),
                          [&](const tbb::blocked_range<std::size_t>& q) {
                            float* __restrict pa = a.data();
                            const float* __restrict pb = b.data();
                            const float* __restrict pc = c.data();
                            for (std::size_t i = q.begin(); i < q.end(); ++i) pa[i] = pb[i] + k * pc[i];
                          });
      }
    });
    const double t = seconds_since(t0);
    if (r > 0) best = std::max(best, 12.0 * static_cast<double>(n) * sweeps / t * 1e-9);
  }
  if (a[n / 2] < 0.0f) std::printf("?");  // keeps the stores
  return best;
}

typedef float F8 __attribute__((vector_size(32)));

// Best GFLOP/s of independent FMA chains on `threads` threads.
double fma_gflops(int threads, int repeat) {
  constexpr int kChains = 10;
  constexpr long kSteps = 20'000'000;  // per thread
  tbb::task_arena arena(threads);
  double best = 0.0;
  for (int r = 0; r < repeat + 1; ++r) {
    float sink = 0.0f;
    const auto t0 = Clock::now();
    arena.execute([&] {
      tbb::parallel_for(0, threads, [&](int t) {
        F8 acc[kChains];
        for (int k = 0; k < kChains; ++k) acc[k] = F8{} + static_cast<float>(k + t);
        const F8 m = F8{} + 0.999999f, add = F8{} + 1e-7f;
        for (long s = 0; s < kSteps; ++s) {
          for (int k = 0; k < kChains; ++k) acc[k] = acc[k] * m + add;  // vfmadd under -march=native
          __asm__ volatile("" : "+x"(acc[0]));                          // no folding of the chain
        }
        F8 total = acc[0];
        for (int k = 1; k < kChains; ++k) total += acc[k];
        if (total[0] < -1.0f) sink += total[0];
      });
    });
    const double t = seconds_since(t0);
    if (r > 0) best = std::max(best, 2.0 * 8 * kChains * kSteps * threads / t * 1e-9);
    if (sink != 0.0f) std::printf("?");
  }
  return best;
}

}  // namespace

int main(int argc, char** argv) {
  int threads = 2;
  int repeat = 5;
  int memory_mib = 768;
  int cache_mib = 12;
  CLI::App cli{"Stream triad bandwidth and FMA peak of this machine (the roofline's limits)"};
  cli.add_option("--threads", threads, "Threads of the parallel runs (the 1-thread ones always run)")
      ->check(CLI::PositiveNumber)
      ->capture_default_str();
  cli.add_option("--repeat", repeat, "Timed repetitions; the best counts")
      ->check(CLI::PositiveNumber)
      ->capture_default_str();
  cli.add_option("--memory-mib", memory_mib, "MiB of the three arrays of the memory triad (past the caches)")
      ->check(CLI::Range(3, 1 << 16))
      ->capture_default_str();
  cli.add_option("--cache-mib", cache_mib, "MiB of the three arrays of the cache triad (inside the last level)")
      ->check(CLI::Range(3, 1 << 16))
      ->capture_default_str();
  try {
    cli.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    const int code = cli.exit(e);
    return code == 0 ? 0 : 2;
  }
  const auto floats = [](int mib) { return (static_cast<std::size_t>(mib) << 20) / 12; };
  fmt::print(
      "{{\"threads\": {}, \"triad_memory_gbs_1\": {:.2f}, \"triad_memory_gbs_n\": {:.2f}, \"triad_cache_gbs_1\": "
      "{:.2f}, "
      "\"triad_cache_gbs_n\": {:.2f}, \"fma_gflops_1\": {:.2f}, \"fma_gflops_n\": {:.2f}}}\n",
      threads, triad_gbs(floats(memory_mib), 1, repeat), triad_gbs(floats(memory_mib), threads, repeat),
      triad_gbs(floats(cache_mib), 1, repeat), triad_gbs(floats(cache_mib), threads, repeat), fma_gflops(1, repeat),
      fma_gflops(threads, repeat));
  return 0;
}
