#include <catch2/catch.hpp>

#include <cmath>

#include "model/cloth_builder.hpp"
#include "scene/scene_loader.hpp"
#include "common/tet_kinematics.h"
#include "solver/xpbd/xpbd_plan.hpp"
#include "solver/xpbd/xpbd_reference.hpp"
#include "util/error.hpp"

using namespace atssim;
using namespace atssim::solver::xpbd;

namespace {

model::Model soft_box(const std::string& gravity) {
  const std::string yaml =
      "simulation: {gravity: " + gravity + "}\n"
      "objects:\n"
      "  - type: solid\n"
      "    box: {size: [0.1, 0.4, 0.1], resolution: [1, 4, 1]}\n"
      "    material: {density: 1000, youngs_modulus: 1.0e7, poisson_ratio: 0.3}\n"
      "    pins: {boxes: [{min: [-1, 0.19, -1], max: [1, 0.21, 1]}]}\n";
  return model::build_model(scene::parse_scene(yaml, "s.yaml", "."));
}

}  // namespace

TEST_CASE("XPBD refuses solids with a message that names the methods that simulate them") {
  const XpbdLayout layout = make_xpbd_layout(soft_box("[0, -9.81, 0]"));
  REQUIRE_FALSE(layout.tets.empty());
  try {
    make_xpbd_plan(layout, {1.0 / 240.0, 4});
    FAIL("expected an error");
  } catch (const Error& e) {
    CHECK(e.exit_code() == 2);
    CHECK(std::string(e.what()).find("vbd") != std::string::npos);
  }
}

TEST_CASE("the rest tets of the layout have F = I") {
  const auto m = soft_box("[0, 0, 0]");
  const XpbdLayout l = make_xpbd_layout(m);
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
