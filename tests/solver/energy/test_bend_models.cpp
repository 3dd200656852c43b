// The two bending models a scene can choose (`bend_model`), as the model
// stage builds them, agree for small folds of a flat stencil; `auto` picks
// the dihedral model exactly when the rest shape is curved.
#include "solver/energy/element_math.hpp"  // first: the double instance of the shared math

#include <catch2/catch.hpp>

#include <cmath>
#include <string>

#include "model/cloth_builder.hpp"
#include "scene/scene_loader.hpp"

using namespace atssim;
using namespace atssim::solver::energy::f64;

namespace {

// Two triangles (0, 1, 2) and (0, 3, 1) sharing the edge 0-1, as a scene
// with one mesh object; `lift` raises vertex 3 out of the plane.
model::Model two_triangles(double lift, const std::string& bend_model) {
  scene::SceneDesc s = scene::parse_scene(
      "objects:\n"
      "  - grid: {size: [1, 1], resolution: [2, 2]}\n"
      "    material: {density: 0.2, stretch_stiffness: 100, bend_stiffness: 0.5, bend_model: " +
          bend_model + "}\n",
      "s.yaml", ".");
  s.objects[0].mesh = {{{0, 0, 0}, {1, 0, 0.2}, {0.4, 0, 0.9}, {0.6, lift, -0.8}}, {{0, 1, 2}, {0, 3, 1}}};
  s.objects[0].grid.reset();
  return model::build_model(s);
}

double energy(const model::Model& m, const ats_vec3 x[4]) {
  const int kind = m.bend.kind[0] == model::BendKind::dihedral ? ATS_BEND_DIHEDRAL : ATS_BEND_ISOMETRIC;
  return ats_bend_element_energy(kind, x, m.bend.weights[0].data(), m.bend.scale[0], 1.0 / m.bend.compliance[0],
                                 m.bend.rest_angle[0]);
}

}  // namespace

TEST_CASE("for a small fold of a flat stencil the dihedral energy equals the isometric one to second order",
          "[energy][bend]") {
  const model::Model iso = two_triangles(0.0, "isometric");
  const model::Model dih = two_triangles(0.0, "dihedral");
  REQUIRE(iso.bend.size() == 1);
  REQUIRE(dih.bend.size() == 1);
  CHECK(dih.bend.rest_angle[0] == 0.0);
  for (double fold : {1e-2, 1e-3}) {
    // Lift the wing vertex out of the plane (a pure bending motion).
    ats_vec3 x[4];
    for (int i = 0; i < 4; ++i) {
      const auto& p = iso.particles.position[iso.bend.stencils[0][i]];
      x[i] = ats_v3(p.x(), p.y(), p.z());
    }
    x[3].y += fold;
    const double e_iso = energy(iso, x), e_dih = energy(dih, x);
    INFO("fold " << fold << ": isometric " << e_iso << ", dihedral " << e_dih);
    CHECK(e_dih == Approx(e_iso).epsilon(10 * fold));
  }
}

TEST_CASE("bend_model auto is isometric on a flat mesh and dihedral on a curved one, with the rest angle kept",
          "[energy][bend]") {
  const model::Model flat = two_triangles(0.0, "auto");
  CHECK(flat.bend.kind[0] == model::BendKind::isometric);
  const model::Model curved = two_triangles(0.3, "auto");
  REQUIRE(curved.bend.kind[0] == model::BendKind::dihedral);
  ats_vec3 x[4];
  for (int i = 0; i < 4; ++i) {
    const auto& p = curved.particles.position[curved.bend.stencils[0][i]];
    x[i] = ats_v3(p.x(), p.y(), p.z());
  }
  CHECK(std::abs(curved.bend.rest_angle[0]) > 0.1);
  CHECK(energy(curved, x) == Approx(0.0).margin(1e-20));  // the rest shape has no bending energy
  // The isometric model of the same curved stencil does not vanish at rest.
  const model::Model forced = two_triangles(0.3, "isometric");
  CHECK(energy(forced, x) > 1e-3);
}
