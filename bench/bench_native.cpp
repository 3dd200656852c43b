// Frame time of the native host loop a user would write instead of atssim:
// the XPBD or VBD substep of the host references (lib/solver/*/
// *_reference.hpp, the kernels' own math), on 1 thread, or with a
// tbb::parallel_for per color in an arena of N threads. scripts/ compares it
// with atssim's device runs on the same scene.
//
//   bench_native --scene scenes/hanging_cloth.yaml --method xpbd|vbd|explicit --resolution N
//                --threads 1|2 --frames F [--warmup W] [--integrator semi_euler|midpoint|rk4]
//                [--shape cloth|solid] [--ordering colors|batches|color_batches]
//                [--loop reference|plain]
// (explicit: the explicit reference's semi-implicit Euler, midpoint or RK4;
// solid: N sets objects.0.box.resolution=[N,N,N] instead of the grid's.)
//
// Prints one line of JSON: method, resolution, threads, frames, median_ms and
// min_ms of a frame (the scene's substeps), checksum, the sum of the final
// positions (shows the work was done and lets runs be compared), and the
// sizes the roofline counts with (substeps, iterations, vertices, stretch,
// bend, tets).
//
// --loop plain (XPBD): the sceptic's baseline instead of the project's host
// reference, bench/plain_xpbd.hpp (colors: a parallel_for per color block),
// bench/plain_xpbd_batches.hpp (batches: float8 lanes, one thread) or
// bench/plain_xpbd_color_batches.hpp (color_batches: the color blocks cut
// into groups of 8 float8 lanes, a parallel_for per block over its groups;
// plain loop only).
#include <algorithm>
#include <chrono>
#include <cstdio>
#include <string>
#include <vector>

#include <fmt/format.h>
#include <CLI/CLI.hpp>

#include <tbb/task_arena.h>

#include "model/cloth_builder.hpp"
#include "plain_xpbd.hpp"
#include "plain_xpbd_batches.hpp"
#include "plain_xpbd_color_batches.hpp"
#include "scene/scene_loader.hpp"
#include "solver/explicit/explicit_reference.hpp"
#include "solver/layout/sim_layout.hpp"
#include "solver/method_registry.hpp"
#include "solver/vbd/vbd_reference.hpp"
#include "solver/xpbd/xpbd_batches.hpp"
#include "solver/xpbd/xpbd_reference.hpp"
#include "util/error.hpp"

using namespace atssim;

namespace {

using Clock = std::chrono::steady_clock;

enum class Method { xpbd, vbd, explicit_rk };

struct Options {
  std::string scene;
  std::string method = "xpbd";
  int resolution = 64;
  int threads = 1;
  int frames = 10;
  int warmup = 3;
  std::string integrator = "semi_euler";
  std::string shape = "cloth";
  int substeps = 0;                 // 0: the scene's
  std::string ordering = "colors";  // xpbd: colors, batches or color_batches (solver/xpbd/xpbd_batches)
  std::string loop = "reference";   // xpbd: reference (the project's host reference) or plain (plain_xpbd.hpp)
};

struct FrameTimes {
  double median_ms = 0.0;
  double min_ms = 0.0;
};

// W untimed frames (first touch, TBB workers starting), then F timed ones.
template <class Reference>
FrameTimes time_frames(Reference& reference, int substeps, const Options& o) {
  for (int f = 0; f < o.warmup; ++f) {
    for (int s = 0; s < substeps; ++s) reference.substep();
  }
  std::vector<double> ms;
  for (int f = 0; f < o.frames; ++f) {
    const auto t0 = Clock::now();
    for (int s = 0; s < substeps; ++s) reference.substep();
    ms.push_back(std::chrono::duration<double, std::milli>(Clock::now() - t0).count());
  }
  std::sort(ms.begin(), ms.end());
  const std::size_t n = ms.size();
  return {n % 2 ? ms[n / 2] : 0.5 * (ms[n / 2 - 1] + ms[n / 2]), ms.front()};
}

double checksum(const std::vector<solver::Float4>& x) {
  double sum = 0.0;
  for (const solver::Float4& p : x) sum += double(p.x) + double(p.y) + double(p.z);
  return sum;
}

int run(const Options& o) {
  const Method method = o.method == "vbd" ? Method::vbd : o.method == "explicit" ? Method::explicit_rk : Method::xpbd;
  std::vector<std::string> overrides{o.shape == "solid"
                                         ? fmt::format("objects.0.box.resolution=[{0},{0},{0}]", o.resolution)
                                         : fmt::format("objects.0.grid.resolution=[{0},{0}]", o.resolution),
                                     "solver.method=" + o.method, "solver.integrator=" + o.integrator};
  if (o.substeps > 0) overrides.push_back(fmt::format("simulation.substeps={}", o.substeps));
  const scene::SceneDesc scene = scene::load_scene_file(o.scene, overrides);
  solver::check_scene(scene, solver::method(o.method));
  const solver::SimLayout layout = solver::make_sim_layout(model::build_model(scene));
  const auto& sim = scene.simulation;
  const double h = sim.frame_dt / sim.substeps;

  FrameTimes times;
  double sum = 0.0;
  if (method == Method::xpbd && o.loop == "plain" && o.ordering == "batches") {
    if (o.threads != 1) throw input_error("--ordering batches runs one thread (--threads 1)");
    bench::PlainXpbdBatches loop(layout, h, sim.iterations);
    times = time_frames(loop, sim.substeps, o);
    sum = checksum(loop.positions());
  } else if (method == Method::xpbd && o.loop == "plain" && o.ordering == "color_batches") {
    bench::PlainXpbdColorBatches loop(layout, h, sim.iterations, o.threads > 1);
    tbb::task_arena arena(o.threads);  // entered once, around every frame
    arena.execute([&] { times = time_frames(loop, sim.substeps, o); });
    sum = checksum(loop.positions());
  } else if (method == Method::xpbd && o.loop == "plain") {
    bench::PlainXpbd loop(layout, h, sim.iterations, o.threads > 1);
    tbb::task_arena arena(o.threads);  // entered once, around every frame
    arena.execute([&] { times = time_frames(loop, sim.substeps, o); });
    sum = checksum(loop.positions());
  } else if (method == Method::xpbd) {
    if (o.ordering == "color_batches")
      throw input_error("--ordering color_batches runs the plain loop only (--loop plain)");
    if (o.ordering == "batches" && o.threads != 1)
      throw input_error("--ordering batches runs one thread (--threads 1)");
    solver::xpbd::XpbdReference reference(o.ordering == "batches" ? solver::xpbd::in_batch_order(layout) : layout,
                                          {h, sim.iterations}, o.threads);
    times = time_frames(reference, sim.substeps, o);
    sum = checksum(reference.state().x);
  } else if (method == Method::explicit_rk) {
    using solver::explicit_rk::Integrator;
    const Integrator integrator = o.integrator == "rk4"        ? Integrator::rk4
                                  : o.integrator == "midpoint" ? Integrator::midpoint
                                                               : Integrator::semi_euler;
    solver::explicit_rk::ExplicitReference reference(layout, {h, integrator}, o.threads);
    times = time_frames(reference, sim.substeps, o);
    sum = checksum(reference.state().x);
  } else {
    if (o.ordering != "colors" && o.ordering != "color_batches")
      throw input_error("vbd: --ordering colors or color_batches");
    solver::vbd::VbdReference reference(layout, h, sim.iterations, o.threads, o.ordering == "color_batches");
    times = time_frames(reference, sim.substeps, o);
    sum = checksum(reference.state().x);
  }
  fmt::print(
      "{{\"method\": \"{}\", \"resolution\": {}, \"threads\": {}, \"frames\": {}, \"median_ms\": {:.4f}, "
      "\"min_ms\": {:.4f}, \"checksum\": {:.9g}, \"substeps\": {}, \"iterations\": {}, \"vertices\": {}, "
      "\"stretch\": {}, \"bend\": {}, \"tets\": {}}}\n",
      o.method, o.resolution, o.threads, o.frames, times.median_ms, times.min_ms, sum, sim.substeps, sim.iterations,
      layout.x.size(), layout.stretch.size(), layout.bend.size(), layout.tets.size());
  return 0;
}

}  // namespace

int main(int argc, char** argv) {
  Options o;
  CLI::App cli{"Frame time of the native host XPBD / VBD / explicit loop (the host references) on 1 or more threads"};
  cli.add_option("--scene", o.scene, "Scene file (YAML); its first object must be a grid cloth")->required();
  cli.add_option("--method", o.method, "xpbd, vbd or explicit")
      ->required()
      ->check(CLI::IsMember({"xpbd", "vbd", "explicit"}));
  cli.add_option("--ordering", o.ordering,
                 "xpbd: colors, batches (the constraints in the order of solver.ordering: batches, one thread) "
                 "or color_batches (--loop plain: each color block cut into groups of 8 float lanes, "
                 "bench/plain_xpbd_color_batches.hpp; 1 or more threads); vbd: colors or color_batches (the "
                 "reference's lanes: each color's vertices in batches of 8 gathered as 8 float lanes)")
      ->check(CLI::IsMember({"colors", "batches", "color_batches"}))
      ->capture_default_str();
  cli.add_option("--loop", o.loop,
                 "xpbd: reference (the project's host reference) or plain (bench/plain_xpbd*.hpp, the "
                 "sceptic's loops over copies of the same arrays)")
      ->check(CLI::IsMember({"reference", "plain"}))
      ->capture_default_str();
  cli.add_option("--integrator", o.integrator, "explicit: semi_euler, midpoint or rk4")
      ->check(CLI::IsMember({"semi_euler", "midpoint", "rk4"}))
      ->capture_default_str();
  cli.add_option("--substeps", o.substeps, "Substeps per frame (0: the scene's)")->check(CLI::NonNegativeNumber);
  cli.add_option("--shape", o.shape, "cloth (grid resolution N x N) or solid (box resolution N x N x N)")
      ->check(CLI::IsMember({"cloth", "solid"}))
      ->capture_default_str();
  cli.add_option("--resolution", o.resolution, "Grid vertices along x and along z")
      ->required()
      ->check(CLI::Range(2, 1 << 15));
  cli.add_option("--threads", o.threads, "1: plain loops; more: tbb::parallel_for per color in an arena")
      ->check(CLI::PositiveNumber)
      ->capture_default_str();
  cli.add_option("--frames", o.frames, "Timed frames")->check(CLI::PositiveNumber)->capture_default_str();
  cli.add_option("--warmup", o.warmup, "Untimed frames first")->check(CLI::NonNegativeNumber)->capture_default_str();
  try {
    cli.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    const int code = cli.exit(e);  // prints help, or the error
    return code == 0 ? 0 : 2;      // bad usage: exit 2, like atssim
  }
  try {
    return run(o);
  } catch (const Error& e) {
    std::fprintf(stderr, "bench_native: %s\n", e.what());
    return e.exit_code();
  }
}
