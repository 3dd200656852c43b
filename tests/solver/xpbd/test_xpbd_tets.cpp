#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>

#include "common/element_types.h"
#include "common/tet_kinematics.h"
#include "model/cloth_builder.hpp"
#include "scene/scene_loader.hpp"
#include "solver/xpbd/xpbd_plan.hpp"
#include "solver/xpbd/xpbd_reference.hpp"
#include "support/positions.hpp"
#include "util/error.hpp"

using namespace atssim;
using namespace atssim::solver;
using namespace atssim::solver::xpbd;
using atssim::test::max_distance;

namespace {

// A 0.1 x 0.4 x 0.1 m bar of 4 cells (24 tets) pinned at its top face.
model::Model soft_box(const std::string& gravity, const std::string& solid_model = "") {
  const std::string model_key = solid_model.empty() ? "" : ", model: " + solid_model;
  const std::string yaml = "simulation: {gravity: " + gravity +
                           "}\n"
                           "objects:\n"
                           "  - type: solid\n"
                           "    box: {size: [0.1, 0.4, 0.1], resolution: [1, 4, 1]}\n"
                           "    material: {density: 1000, youngs_modulus: 1.0e7, poisson_ratio: 0.3" +
                           model_key +
                           "}\n"
                           "    pins: {boxes: [{min: [-1, 0.19, -1], max: [1, 0.21, 1]}]}\n";
  return model::build_model(scene::parse_scene(yaml, "s.yaml", "."));
}

}  // namespace

TEST_CASE("XPBD refuses neo-Hookean solids (the default model) and says to use stvk or another method") {
  const SimLayout layout = make_sim_layout(soft_box("[0, -9.81, 0]"));
  REQUIRE_FALSE(layout.tets.empty());
  CHECK(layout.tets.front().model == ATS_TET_NEO_HOOKEAN);  // the scene default is unchanged
  try {
    make_xpbd_plan(layout, {1.0 / 240.0, 4});
    FAIL("expected an error");
  } catch (const Error& e) {
    const std::string what = e.what();
    CHECK(e.exit_code() == 2);
    CHECK(what.find("stvk") != std::string::npos);
    CHECK(what.find("another solver.method") != std::string::npos);
    CHECK(what.find("atssim methods") != std::string::npos);
  }
}

TEST_CASE("an XPBD StVK solid sweeps every tet color block once per iteration") {
  const int iterations = 3;
  const SimLayout layout = make_sim_layout(soft_box("[0, -9.81, 0]", "stvk"));
  XpbdBuffers ids;
  const auto plan = make_xpbd_plan(layout, {1.0 / 240.0, iterations}, &ids);
  const int blocks = static_cast<int>(layout.tet_blocks.size()) - 1;
  REQUIRE(blocks > 1);
  CHECK(plan.tasks_of(solver::xpbd::kTet).size() == std::size_t(iterations * blocks));
  CHECK(plan.graph.size() == std::size_t(2 + iterations * blocks));  // predict, tets, update velocity
  REQUIRE(ids.tet_lambda >= 0);
  CHECK(plan.buffers[ids.tet_lambda].initial.size() == layout.tets.size() * 8 * sizeof(float));
  int covered = 0;
  for (sched::TaskId t : plan.tasks_of(solver::xpbd::kTet)) {
    const auto& launch = plan.launches[t].front();
    CHECK(launch.function == "xpbd_tet");
    CHECK(plan.launches[t].size() == 1);  // one launch over a range: split_plan may cut it
    CHECK(launch.args[4].i32 == (plan.graph.task(t).iteration == 0 ? 1 : 0));  // lambdas reset per substep
    if (plan.graph.task(t).iteration == 0) covered += launch.range.count;
  }
  CHECK(covered == static_cast<int>(layout.tets.size()));
}

TEST_CASE("the host XPBD keeps a pinned StVK bar at rest without gravity") {
  const SimLayout layout = make_sim_layout(soft_box("[0, 0, 0]", "stvk"));
  XpbdReference ref(layout, {1.0 / 240.0, 10});
  for (int s = 0; s < 20; ++s) ref.substep();
  const double drift = max_distance(ref.state().x, layout.x);
  INFO("max drift " << drift << " m");
  CHECK(drift < 1e-6);
}

TEST_CASE("the host XPBD residual of a falling StVK bar falls as iterations rise") {
  const auto m = soft_box("[0, -9.81, 0]", "stvk");
  double previous = 1e30;
  for (int iterations : {1, 4, 16, 64}) {
    XpbdReference ref(make_sim_layout(m), {1.0 / 240.0, iterations});
    for (int s = 0; s < 5; ++s) ref.substep();
    const double r = ref.residual_rms();
    INFO("iterations " << iterations << " residual " << r);
    CHECK(r < previous);
    previous = r;
  }
}

TEST_CASE("the rest tets of the layout have F = I") {
  const auto m = soft_box("[0, 0, 0]");
  const SimLayout l = make_sim_layout(m);
  double worst = 0.0;
  for (const auto& t : l.tets) {
    ats_mat3 dm;
    for (int r = 0; r < 3; ++r) dm.r[r] = ats_v3(t.dm_inv[3 * r], t.dm_inv[3 * r + 1], t.dm_inv[3 * r + 2]);
    ats_vec3 x[4];
    for (int j = 0; j < 4; ++j) x[j] = ats_v3(l.x[t.v[j]].x, l.x[t.v[j]].y, l.x[t.v[j]].z);
    const ats_mat3 f = ats_tet_deformation(x, dm);
    const ats_mat3 i = ats_m3_diag(1);
    for (int r = 0; r < 3; ++r) {
      worst = std::max({worst, double(std::abs(f.r[r].x - i.r[r].x)), double(std::abs(f.r[r].y - i.r[r].y)),
                        double(std::abs(f.r[r].z - i.r[r].z))});
    }
  }
  CHECK(worst < 1e-5);
}
