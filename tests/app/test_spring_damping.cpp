// Material damping along springs (issue #13, `material.damping`: Rayleigh
// stiffness-proportional beta, c = beta k per spring): the decay of a damped
// spring-mass oscillator per period against each integrator's own analytic
// step, the stability limit it implies, and the default that changes nothing.
#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>
#include <complex>
#include <string>
#include <vector>

#include <fmt/format.h>

#include "app/convergence.hpp"
#include "app/simulation.hpp"
#include "io/result_reader.hpp"
#include "solver/explicit/stability_limit.hpp"
#include "support/methods.hpp"
#include "support/scenes.hpp"
#include "support/temp_dir.hpp"

using namespace atssim;

namespace {

constexpr double kPi = 3.14159265358979323846;

// One mass on one spring, as in test_explicit.cpp: a 2 x 2 grid with three
// corners pinned, the free corner (vertex 3, m = 1/30 kg) at the origin;
// gravity along +z stretches its spring to vertex 1 (along z, stiffness k).
// Its other spring (to vertex 2) is perpendicular, so the motion along z is
// one mode with w² = k/m and, from c = beta k along the z spring, the rate
// g = c/m = beta w² (the perpendicular spring's terms are second order in
// the 3 mm amplitude).
constexpr double kMass = 0.2 * 0.5 / 3.0;

std::string oscillator_yaml(double k, double beta, double fps, int substeps, int frames, const std::string& method,
                            const std::string& integrator) {
  return fmt::format(
      "simulation: {{fps: {}, substeps: {}, iterations: 16, frames: {}, gravity: [0, 0, 9.81]}}\n"
      "objects:\n"
      "  - grid: {{size: [1, 1], resolution: [2, 2]}}\n"
      "    transform: {{translate: [-0.5, 0, -0.5]}}\n"
      "    material: {{density: 0.2, stretch_stiffness: {}, damping: {}}}\n"
      "    pins: {{vertices: [0, 1, 2]}}\n"
      "solver: {{method: {}, integrator: {}}}\n",
      fps, substeps, frames, k, beta, method, integrator);
}

struct OscillatorCase {
  std::string method, integrator;
};

// Every method; one with a choice of integrator (solver.integrator: the
// explicit one) once with each.
std::vector<OscillatorCase> oscillator_cases() {
  std::vector<OscillatorCase> out;
  for (const solver::MethodDescription* m : solver::methods()) {
    std::size_t before = out.size();
    for (const solver::MethodOption& o : m->options) {
      if (o.key != "integrator") continue;
      for (std::string_view choice : o.choices) out.push_back({std::string(m->name), std::string(choice)});
    }
    if (out.size() == before) out.push_back({std::string(m->name), "semi_euler"});
  }
  return out;
}

std::vector<double> oscillator_z(const test::TempDir& dir, const std::string& yaml, int frames) {
  app::RunOptions o;
  o.scene_path = dir.write("osc.yaml", yaml);
  o.overrides = {"output.path=" + dir.file("osc.h5"), "devices=cpu"};
  app::run_simulation(o);
  std::vector<double> z;
  for (int f = 0; f <= frames; ++f) z.push_back(io::read_frame_positions(dir.file("osc.h5"), f)[3 * 3 + 2]);
  return z;
}

// Maxima of z - z_eq, each refined by a parabola through its neighbours.
std::vector<double> peaks(const std::vector<double>& z, double z_eq) {
  std::vector<double> out;
  for (std::size_t i = 1; i + 1 < z.size(); ++i) {
    const double a = z[i - 1] - z_eq, b = z[i] - z_eq, c = z[i + 1] - z_eq;
    if (b > a && b >= c && b > 0) {
      const double den = a - 2 * b + c;
      out.push_back(den < 0 ? b - 0.125 * (a - c) * (a - c) / den : b);
    }
  }
  return out;
}

// The amplitude ratio per period of a linear step z_{n+1} = S z_n: S's
// eigenvalue r e^(i phi) takes 2 pi/phi steps per period.
double ratio_per_period(std::complex<double> eigenvalue) {
  return std::pow(std::abs(eigenvalue), 2.0 * kPi / std::abs(std::arg(eigenvalue)));
}

// Each integrator's step on z'' = -w² z - g z', written out here (not the
// library's): semi-implicit Euler from its 2 x 2 matrix (trace, det);
// midpoint and RK4 as R(h lambda), lambda = -g/2 + i sqrt(w² - g²/4);
// backward Euler (the implicit methods' substep) as 1/(1 - h lambda).
std::complex<double> step_eigenvalue(const std::string& integrator, double w2, double g, double h) {
  using C = std::complex<double>;
  if (integrator == "semi_euler") {
    const double tr = 2.0 - h * h * w2 - h * g, det = 1.0 - h * g;
    return C(0.5 * tr, std::sqrt(det - 0.25 * tr * tr));
  }
  const C z = h * C(-0.5 * g, std::sqrt(w2 - 0.25 * g * g));
  if (integrator == "midpoint") return 1.0 + z + z * z / 2.0;
  if (integrator == "rk4") return 1.0 + z + z * z / 2.0 + z * z * z / 6.0 + z * z * z * z / 24.0;
  return 1.0 / (1.0 - z);  // implicit Euler
}

}  // namespace

TEST_CASE("spring damping: a damped oscillator's amplitude ratio per period is the integrator's own, within 1 %",
          "[damping][spring_damping]") {
  const OscillatorCase c = GENERATE(from_range(oscillator_cases()));
  const double k = 100.0, beta = 0.002;  // w = 54.8 1/s, g = 6 1/s: e^(-g T/2) = 0.71
  const double fps = 600.0;
  const int substeps = 4, frames = 600;  // h = 1/2400 s, 1 s
  test::TempDir dir;
  const std::vector<double> z =
      oscillator_z(dir, oscillator_yaml(k, beta, fps, substeps, frames, c.method, c.integrator), frames);
  const double w2 = k / kMass, g = beta * w2, h = 1.0 / (fps * substeps);
  const std::vector<double> p = peaks(z, z[0] + kMass * 9.81 / k);
  REQUIRE(p.size() >= 4);
  const double measured = std::pow(p[3] / p[0], 1.0 / 3.0);
  const bool implicit = solver::method(c.method).implicit;
  const double own = ratio_per_period(step_eigenvalue(implicit ? "implicit" : c.integrator, w2, g, h));
  const double undamped = ratio_per_period(step_eigenvalue(implicit ? "implicit" : c.integrator, w2, 0.0, h));
  const double continuous = std::exp(-0.5 * g * 2.0 * kPi / std::sqrt(w2 - 0.25 * g * g));
  INFO(c.method << " " << c.integrator << ": ratio per period " << measured << "; the step's own " << own
                << ", continuous " << continuous << ", the step without damping " << undamped);
  CHECK(measured == Approx(own).epsilon(0.01));
  CHECK(std::abs(measured - undamped) > 0.1);  // the damping did it
}

TEST_CASE("spring damping: the stable step of semi-implicit Euler is (sqrt(g² + 4 w²) - g)/w², g = beta w²",
          "[damping][spring_damping]") {
  using namespace solver::explicit_rk;
  const double w2 = GENERATE(1e2, 1e4, 1e8);
  const double beta = GENERATE(1e-6, 1e-3, 1e-1);
  const double g = beta * w2;
  const double closed = (std::sqrt(g * g + 4.0 * w2) - g) / w2;
  CHECK(stable_step(Integrator::semi_euler, w2, 0.0, beta) == Approx(closed).epsilon(1e-6));
  // RK4 and midpoint: the boundary of |R(h lambda)| ≤ 1 (+1e-4 for midpoint) for both eigenvalues of
  // the mode (overdamped ones are real).
  for (Integrator integrator : {Integrator::midpoint, Integrator::rk4}) {
    const double limit = stable_step(integrator, w2, 0.0, beta);
    const auto growth = [&](double h) {
      const std::complex<double> root = std::sqrt(std::complex<double>(0.25 * g * g - w2));
      double worst = 0.0;
      for (const std::complex<double> lambda : {-0.5 * g + root, -0.5 * g - root}) {
        const std::complex<double> z = h * lambda;
        const std::complex<double> r = integrator == Integrator::midpoint
                                           ? 1.0 + z + z * z / 2.0
                                           : 1.0 + z + z * z / 2.0 + z * z * z / 6.0 + z * z * z * z / 24.0;
        worst = std::max(worst, std::abs(r));
      }
      return worst;
    };
    const double tolerance = integrator == Integrator::midpoint ? 1e-4 : 1e-9;
    INFO("w² " << w2 << ", beta " << beta << ", integrator " << static_cast<int>(integrator) << ": limit " << limit);
    CHECK(growth(0.999 * limit) <= 1.0 + tolerance);
    CHECK(growth(1.001 * limit) > 1.0 + tolerance);
  }
  // Without damping: the closed forms of the undamped limit.
  CHECK(stable_step(Integrator::rk4, w2, 0.0, 0.0) == stable_step(Integrator::rk4, w2));
}

TEST_CASE("spring damping: damping 0 is the undamped run, bit for bit, under every method",
          "[damping][spring_damping]") {
  const std::string method =
      GENERATE(from_range(test::methods_where([](const solver::MethodDescription&) { return true; })));
  const std::string base =
      "simulation: {fps: 60, substeps: 40, iterations: 4, frames: 5}\n"
      "objects:\n"
      "  - grid: {size: [1, 1], resolution: [8, 8]}\n"
      "    transform: {translate: [0, 1.5, 0]}\n"
      "    material: {density: 0.2, stretch_stiffness: 1000, bend_stiffness: 0.001";
  const std::string tail = "}\n    pins: {vertices: [56, 63]}\n";
  test::TempDir dir;
  std::vector<std::vector<float>> out;
  for (const std::string& extra : {std::string(), std::string(", damping: 0"), std::string(", damping: 0.0001")}) {
    app::RunOptions o;
    o.scene_path = dir.write("cloth.yaml", base + extra + tail);
    o.overrides = {"output.path=" + dir.file("cloth.h5"), "devices=cpu", "solver.method=" + method};
    app::run_simulation(o);
    out.push_back(io::read_frame_positions(dir.file("cloth.h5"), 5));
  }
  CHECK(out[0] == out[1]);
  CHECK(out[0] != out[2]);  // the control: damping changes the run
}

TEST_CASE("spring damping: converge minimises the damped potential, and the vertex methods reach its minimum",
          "[damping][spring_damping]") {
  // If a method's kernels and the Newton reference disagreed about the
  // damping term, y_k would stall above 0 (or fall below it).
  test::TempDir dir;
  app::ConvergeOptions o;
  o.scene_path = dir.write("cloth.yaml", test::hanging_cloth_yaml(10, 1e3, 1e-3, 8));
  o.overrides = {"devices=cpu", "objects.0.material.damping=0.01"};
  o.methods = {"vbd", "jpgd", "xpbd"};
  o.max_iterations = 256;
  o.frames_before = 3;
  o.timing_repeats = 1;
  const io::ConvergenceResult damped = app::run_convergence(o);
  o.overrides = {"devices=cpu"};
  const io::ConvergenceResult plain = app::run_convergence(o);
  CHECK(damped.newton_status == "converged");
  INFO("E* damped " << damped.energy_reference << ", undamped " << plain.energy_reference);
  CHECK(std::abs(damped.energy_reference - plain.energy_reference) > 1e-6 * std::abs(plain.energy_reference));
  REQUIRE(damped.traces.size() == 3);
  for (const auto& t : damped.traces) {
    INFO(t.variant << ": y at k = 1 " << t.relative_error.front() << ", at k = " << t.iterations.back() << " "
                   << t.relative_error.back());
    for (double e : t.energy) CHECK(e >= damped.energy_reference - 1e-9 * std::abs(damped.energy_reference));
    if (t.variant.rfind("xpbd", 0) != 0) CHECK(t.relative_error.back() < 0.01);
  }
}

namespace {

// The highest the cloth's centroid gets in frames 45 to 60 (the swing to the
// far side; it starts at 1.5 m, horizontal).
double far_swing_height(const test::TempDir& dir, const std::vector<std::string>& sets) {
  app::RunOptions o;
  o.scene_path = std::string(ATSSIM_SOURCE_DIR) + "/scenes/hanging_cloth.yaml";
  o.overrides = {"output.path=" + dir.file("swing.h5"), "devices=cpu", "simulation.frames=60",
                 "objects.0.grid.resolution=[16,16]"};
  o.overrides.insert(o.overrides.end(), sets.begin(), sets.end());
  app::run_simulation(o);
  double highest = -1e30;
  for (int f = 45; f <= 60; ++f) {
    const std::vector<float> x = io::read_frame_positions(dir.file("swing.h5"), f);
    double y = 0.0;
    for (std::size_t i = 1; i < x.size(); i += 3) y += x[i];
    highest = std::max(highest, y / static_cast<double>(x.size() / 3));
  }
  return highest;
}

}  // namespace

// Measured (16 x 16, XPBD): undamped 1.449 m, spring damping 0.01 s 1.436 m,
// air drag 1/s 1.192 m. Spring damping resists stretching rates only, and the
// swing about the pinned edge is nearly rigid: the mass-proportional half of
// Rayleigh damping (air drag) is what stops it.
TEST_CASE("the default hanging cloth, released horizontally, no longer swings back up to its start with air drag",
          "[damping][spring_damping]") {
  test::TempDir dir;
  const double undamped = far_swing_height(dir, {});
  const double springs = far_swing_height(dir, {"objects.0.material.damping=0.01"});
  const double drag = far_swing_height(dir, {"simulation.air_drag=1"});
  INFO("highest centroid in frames 45-60 (start 1.5 m): undamped " << undamped << " m, spring damping " << springs
                                                                   << " m, air drag " << drag << " m");
  CHECK(undamped > 1.4);
  CHECK(drag < undamped - 0.2);
  CHECK(springs < undamped);
}
