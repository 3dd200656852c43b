// One cell of the stability matrix (issue #13, scripts/stability_matrix.py):
// a small hanging cloth under one method, stretch stiffness, substep, mass
// ratio, iteration count and start state, run on one device while the
// closed system's total energy is measured every frame.
//
//   stability_cell --method vbd --stiffness 1e6 --substep 0.01 [--integrator rk4]
//                  [--mass-ratio 1e3] [--iterations 8] [--state normal|degenerate|inverted]
//                  [--density 0.2] [--grid 8] [--substeps-per-frame 10] [--frames 20]
//
// The cloth: grid × grid vertices, 1 m, pinned at two corners (pins do no
// work), gravity −9.81 y, bending 1e-4 N·m, no drag and no damping. Mass
// ratio r: every vertex with i + k odd gets r times its lumped mass. States:
// degenerate = the centre vertex starts on its +x neighbour (a zero-length
// spring, two zero-area triangles); inverted = the centre vertex starts 1.5
// edge lengths beyond that neighbour (its triangles folded over).
//
// Energy E = Σ ½ m |v|² − Σ m g·x + stretch + bending energies (the solvers'
// own element energies, in double). Prints one line of JSON: outcome
// ("pass", "fail" or "refused"), the refusal's message, frames run, whether
// every frame stayed finite, E at the start, the largest rise of E above its
// start and above its running minimum, the tolerance, and the centroid's drop
// against free fall. A cell fails when a frame is not finite or E rises
// above its start by more than tolerance = 1e-2 S, S = M |g| D + |E_elastic,0|
// + KE_0 (M the total mass, D the cloth's rest diagonal): energy grew without
// a source.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <string>
#include <vector>

#include <fmt/format.h>
#include <CLI/CLI.hpp>

#include "app/scene_checks.hpp"
#include "device/device_set.hpp"
#include "device/plan_executor.hpp"
#include "model/cloth_builder.hpp"
#include "plan/buffer.hpp"
#include "plan/plan_state.hpp"
#include "scene/scene_loader.hpp"
#include "solver/energy/incremental_potential.hpp"
#include "solver/energy/potential_evaluation.hpp"
#include "solver/layout/sim_layout.hpp"
#include "solver/method_registry.hpp"
#include "solver/vertex/stiffness_ratio.hpp"
#include "util/error.hpp"

using namespace atssim;

namespace {

struct Options {
  std::string method = "xpbd";
  std::string integrator = "semi_euler";
  double stiffness = 1e4;
  double substep = 1e-2;
  double mass_ratio = 1.0;
  int iterations = 8;
  std::string state = "normal";
  double density = 0.2;
  int grid = 8;
  int substeps_per_frame = 10;
  int frames = 20;
};

std::string scene_text(const Options& o) {
  const double frame_dt = o.substep * o.substeps_per_frame;
  return fmt::format(
      "simulation: {{dt: {:.17g}, substeps: {}, iterations: {}, frames: {}, gravity: [0, -9.81, 0]}}\n"
      "objects:\n"
      "  - grid: {{size: [1, 1], resolution: [{}, {}]}}\n"
      "    transform: {{translate: [0, 1.5, 0]}}\n"
      "    material: {{density: {:.17g}, stretch_stiffness: {:.17g}, bend_stiffness: 1.0e-4}}\n"
      "    pins: {{vertices: [{}, {}]}}\n"
      "solver: {{method: {}, integrator: {}}}\n"
      "devices: cpu\n",
      frame_dt, o.substeps_per_frame, o.iterations, o.frames, o.grid, o.grid, o.density, o.stiffness,
      o.grid * (o.grid - 1), o.grid * o.grid - 1, o.method, o.integrator);
}

struct Energy {
  double kinetic = 0.0, gravity = 0.0, elastic = 0.0;
  double total() const { return kinetic + gravity + elastic; }
};

Energy energy_of(const solver::SimLayout& layout, const std::vector<double>& mass, const std::vector<solver::Float4>& x,
                 const std::vector<solver::Float4>& v, double h) {
  Energy e;
  const solver::Float4 g = layout.gravity;
  for (std::size_t i = 0; i < x.size(); ++i) {
    e.gravity -= mass[i] * (double(g.x) * x[i].x + double(g.y) * x[i].y + double(g.z) * x[i].z);
    if (layout.x[i].w == 0.0f) continue;
    e.kinetic += 0.5 * mass[i] * (double(v[i].x) * v[i].x + double(v[i].y) * v[i].y + double(v[i].z) * v[i].z);
  }
  solver::SimLayout at = layout;
  at.x = x;
  const solver::energy::IncrementalPotential p = solver::energy::make_incremental_potential(at, x, h, &x);
  const solver::energy::EnergyTerms t = solver::energy::energy_terms(p, solver::energy::positions_of(x));
  e.elastic = t.stretch + t.bend + t.tet;
  return e;
}

double centroid_y(const std::vector<solver::Float4>& x) {
  double s = 0.0;
  for (const auto& p : x) s += p.y;
  return s / static_cast<double>(x.size());
}

bool finite(const std::vector<solver::Float4>& a) {
  for (const auto& p : a) {
    if (!std::isfinite(p.x) || !std::isfinite(p.y) || !std::isfinite(p.z)) return false;
  }
  return true;
}

std::string json_string(const std::string& s) {
  std::string out = "\"";
  for (char c : s) {
    if (c == '"' || c == '\\') out += '\\';
    if (static_cast<unsigned char>(c) < 0x20) continue;
    out += c;
  }
  return out + "\"";
}

int run(const Options& o) {
  const scene::SceneDesc scene = scene::parse_scene(scene_text(o), "cell.yaml", ".");
  model::Model model = model::build_model(scene);
  // Mass ratio: a checkerboard of heavier vertices.
  for (std::size_t i = 0; i < model.particles.size(); ++i) {
    const int col = static_cast<int>(i) % o.grid, row = static_cast<int>(i) / o.grid;
    if ((col + row) % 2 == 1) {
      model.particles.mass[i] *= o.mass_ratio;
      if (model.particles.inv_mass[i] > 0.0) model.particles.inv_mass[i] = 1.0 / model.particles.mass[i];
    }
  }
  const int centre = (o.grid / 2) * o.grid + o.grid / 2;
  const double edge = 1.0 / (o.grid - 1);
  if (o.state == "degenerate") {
    model.particles.position[centre] = model.particles.position[centre + 1];
  } else if (o.state == "inverted") {
    model.particles.position[centre].x() += 1.5 * edge + edge;
  }
  solver::SimLayout layout = solver::make_sim_layout(model);
  const double h = o.substep;
  double total_mass = 0.0;
  for (double m : model.particles.mass) total_mass += m;

  const double kappa = solver::vertex::stiffness_to_inertia(layout, h);  // h² λmax(M⁻¹K)
  const solver::MethodDescription& method = solver::method(o.method);
  plan::SubstepPlan plan;
  try {
    solver::check_scene(scene, method);
    plan = method.build(layout, solver::method_settings(scene, method));
  } catch (const Error& e) {
    if (e.kind() != ErrorKind::input) throw;
    fmt::print("{{\"outcome\": \"refused\", \"message\": {}, \"stiffness_to_inertia\": {:.3g}}}\n",
               json_string(e.what()), kappa);
    return 0;
  }
  const device::DeviceSet devices = app::open_scene_devices(scene);
  // The events executor: on a loaded machine the fused one's spin waits starve each other.
  device::ExecutorOptions options;
  options.kind = device::ExecutorKind::events;
  device::PlanExecutor executor(devices, std::move(plan), options);

  const Energy e0 = energy_of(layout, model.particles.mass, layout.x, layout.v, h);
  const double scale = total_mass * 9.81 * std::sqrt(2.0) + std::abs(e0.elastic) + e0.kinetic;
  const double tolerance = 1e-2 * scale;
  const double y0 = centroid_y(layout.x);
  double rise = 0.0, rise_over_min = 0.0, running_min = e0.total(), drop = 0.0;
  int frames_run = 0;
  bool all_finite = true;
  for (int f = 1; f <= o.frames; ++f) {
    executor.run_substeps(o.substeps_per_frame);
    const plan::PlanState s = executor.read_state();
    const std::vector<solver::Float4> x = plan::values_of<solver::Float4>(s.positions);
    const std::vector<solver::Float4> v = plan::values_of<solver::Float4>(s.velocities);
    frames_run = f;
    if (!finite(x) || !finite(v)) {
      all_finite = false;
      break;
    }
    const double e = energy_of(layout, model.particles.mass, x, v, h).total();
    if (!std::isfinite(e)) {
      all_finite = false;
      break;
    }
    rise = std::max(rise, e - e0.total());
    rise_over_min = std::max(rise_over_min, e - running_min);
    running_min = std::min(running_min, e);
    drop = y0 - centroid_y(x);
  }
  const double t = frames_run * o.substeps_per_frame * h;
  const bool pass = all_finite && rise <= tolerance;
  fmt::print(
      "{{\"outcome\": \"{}\", \"frames\": {}, \"finite\": {}, \"energy_start\": {:.9g}, \"rise\": {:.6g}, "
      "\"rise_over_min\": {:.6g}, \"tolerance\": {:.6g}, \"drop\": {:.6g}, \"free_fall\": {:.6g}, "
      "\"stiffness_to_inertia\": {:.3g}}}\n",
      pass ? "pass" : "fail", frames_run, all_finite ? "true" : "false", e0.total(), rise, rise_over_min, tolerance,
      drop, 0.5 * 9.81 * t * t, kappa);
  return 0;
}

}  // namespace

int main(int argc, char** argv) {
  Options o;
  CLI::App cli{"One cell of the stability matrix: finite, and no energy growth without a source"};
  cli.add_option("--method", o.method)->required();
  cli.add_option("--integrator", o.integrator)->capture_default_str();
  cli.add_option("--stiffness", o.stiffness, "stretch stiffness, N/m")->capture_default_str();
  cli.add_option("--substep", o.substep, "h, s")->capture_default_str();
  cli.add_option("--mass-ratio", o.mass_ratio)->capture_default_str();
  cli.add_option("--iterations", o.iterations)->capture_default_str();
  cli.add_option("--state", o.state)->check(CLI::IsMember({"normal", "degenerate", "inverted"}))->capture_default_str();
  cli.add_option("--density", o.density, "kg/m²")->capture_default_str();
  cli.add_option("--grid", o.grid)->check(CLI::Range(3, 256))->capture_default_str();
  cli.add_option("--substeps-per-frame", o.substeps_per_frame)->capture_default_str();
  cli.add_option("--frames", o.frames)->capture_default_str();
  try {
    cli.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    const int code = cli.exit(e);
    return code == 0 ? 0 : 2;
  }
  try {
    return run(o);
  } catch (const Error& e) {
    std::fprintf(stderr, "stability_cell: %s\n", e.what());
    return e.exit_code();
  }
}
