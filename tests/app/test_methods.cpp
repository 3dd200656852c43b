#include <catch2/catch.hpp>

#include "app/convergence.hpp"
#include "support/descent_checks.hpp"
#include "support/methods.hpp"
#include "support/scenes.hpp"
#include "support/temp_dir.hpp"

using namespace atssim;

TEST_CASE("every descent method lowers the energy, its error falls with iterations, and two devices change nothing") {
  test::TempDir dir;
  app::ConvergeOptions o;
  o.scene_path = dir.write("cloth.yaml", test::hanging_cloth_yaml(16, 1e3, 1e-3, 8));
  o.overrides = {"devices=cpu/2"};
  o.methods = test::descent_methods();  // VBD, SOSD, JPGD
  o.schedules = {"single", "split", "heft"};
  o.max_iterations = 32;
  o.frames_before = 3;
  o.timing_repeats = 1;
  const io::ConvergenceResult r = app::run_convergence(o);
  REQUIRE(r.newton_status == "converged");
  REQUIRE(r.traces.size() == 3 * o.methods.size());  // method × schedule, schedules inner
  for (std::size_t v = 0; v < r.traces.size(); ++v) {
    const auto& t = r.traces[v];
    INFO(t.variant);
    CHECK(t.variant == o.methods[v / 3] + "/" + o.schedules[v % 3]);
    test::check_descends(r, t);
    for (double e : t.energy) CHECK(e < r.energy_start);  // the substep lowered E below E(x~)
    CHECK(t.relative_error.back() < 0.05);
    // split and heft run the same iteration on two devices as single: the same energies.
    if (v % 3 == 0) continue;
    const auto& single = r.traces[v - v % 3];
    REQUIRE(single.energy.size() == t.energy.size());
    for (std::size_t i = 0; i < t.energy.size(); ++i) CHECK(t.energy[i] == single.energy[i]);
  }
}

TEST_CASE("JPGD with heavy-ball momentum descends, and faster than without acceleration") {
  test::TempDir dir;
  const auto run = [&](const std::string& acceleration) {
    app::ConvergeOptions o;
    o.scene_path = dir.write("cloth.yaml", test::hanging_cloth_yaml(16, 1e3, 1e-3, 8));
    o.overrides = {"devices=cpu", acceleration};
    o.methods = {"jpgd"};
    o.max_iterations = 32;
    o.frames_before = 3;
    o.timing_repeats = 1;
    return app::run_convergence(o);
  };
  const io::ConvergenceResult momentum = run("solver.momentum=0.5");
  const io::ConvergenceResult plain = run("solver.chebyshev_rho=0");
  REQUIRE(momentum.traces.size() == 1);
  const auto& m = momentum.traces[0];
  const auto& p = plain.traces[0];
  REQUIRE(m.relative_error.size() == p.relative_error.size());
  CHECK(m.relative_error[0] == p.relative_error[0]);  // the first step has no history
  for (std::size_t i = 0; i < m.energy.size(); ++i) {
    CHECK(m.energy[i] < momentum.energy_start);
    CHECK(m.energy[i] >= momentum.energy_reference);
    if (i > 0) CHECK(m.relative_error[i] < m.relative_error[i - 1]);
  }
  CHECK(m.relative_error.back() < 0.8 * p.relative_error.back());  // measured 0.034 vs 0.056
}
