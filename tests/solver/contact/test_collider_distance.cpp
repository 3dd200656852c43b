#include <catch2/catch.hpp>

#include <cmath>
#include <cstdint>
#include <vector>

#include "common/collider_distance.h"
#include "model/collider.hpp"
#include "solver/contact/contact_summary.hpp"
#include "solver/layout/sim_layout.hpp"

using namespace atssim;

namespace {

ats_collider_c record(const scene::ColliderDesc& d) {
  return solver::collider_records(model::make_colliders({d})).front();
}

double gap(const ats_collider_c& c, double x, double y, double z) {
  return ats_collider_gap(&c, ats_v3(float(x), float(y), float(z))).phi;
}

}  // namespace

TEST_CASE("signed distances of the four shapes match their closed forms") {
  scene::ColliderDesc plane;
  plane.shape = scene::ColliderShape::plane;
  plane.point = {0, 1, 0};
  plane.normal = {1, 1, 0};  // normalised by the model
  plane.thickness = 0.01;
  CHECK(gap(record(plane), 1, 1, 0) == Approx(1 / std::sqrt(2.0) - 0.01).margin(1e-6));

  scene::ColliderDesc sphere;
  sphere.shape = scene::ColliderShape::sphere;
  sphere.point = {0, 0.5, 0};
  sphere.radius = 0.3;
  sphere.thickness = 0.01;
  CHECK(gap(record(sphere), 0, 1.0, 0) == Approx(0.5 - 0.3 - 0.01).margin(1e-6));
  CHECK(gap(record(sphere), 0.1, 0.5, 0) == Approx(-0.2 - 0.01).margin(1e-6));

  scene::ColliderDesc capsule;
  capsule.shape = scene::ColliderShape::capsule;
  capsule.point = {0, 0, 0};
  capsule.end = {1, 0, 0};
  capsule.radius = 0.1;
  capsule.thickness = 0.01;
  CHECK(gap(record(capsule), 0.5, 0.4, 0) == Approx(0.3 - 0.01).margin(1e-6));        // beside the axis
  CHECK(gap(record(capsule), 1.3, 0.4, 0) == Approx(0.5 - 0.1 - 0.01).margin(1e-6));  // beyond end b

  scene::ColliderDesc box;
  box.shape = scene::ColliderShape::box;
  box.point = {0, 0, 0};
  box.size = {2, 1, 1};
  box.rotate_deg = {0, 0, 90};  // its local x now points along world y
  box.thickness = 0.01;
  const ats_collider_c b = record(box);
  CHECK(gap(b, 0, 1.5, 0) == Approx(0.5 - 0.01).margin(1e-6));     // above the face at y = 1
  CHECK(gap(b, 0.5, 0, 0) == Approx(0.0 - 0.01).margin(1e-6));     // on the face at x = 0.5
  CHECK(gap(b, 0.8, 1.4, 0) == Approx(0.5 - 0.01).margin(1e-6));   // off the edge (0.5, 1): |(0.3, 0.4)|
  CHECK(gap(b, 0.1, 0.0, 0) == Approx(-0.4 - 0.01).margin(1e-6));  // inside, nearest face x = 0.5
  const ats_surface_distance inside = ats_collider_distance(&b, ats_v3(0.1f, 0.0f, 0.0f));
  CHECK(inside.n.x == Approx(1.0).margin(1e-6));
}

TEST_CASE("the contact energy's gradient is its finite difference, and it vanishes outside the thickness") {
  scene::ColliderDesc sphere;
  sphere.shape = scene::ColliderShape::sphere;
  sphere.point = {0, 0, 0};
  sphere.radius = 0.5;
  sphere.thickness = 0.05;
  sphere.stiffness = 10;
  const ats_collider_c c = record(sphere);
  const float mass = 0.01f, inv_h2 = 1e4f;
  const ats_vec3 x = ats_v3(0.3f, 0.35f, 0.1f);  // |x| = 0.472: 7.8 cm inside the thickened surface
  const ats_vec3 g = ats_contact_gradient(&c, x, mass, inv_h2);
  const float e = 1e-3f;
  const float fd_x = (ats_contact_energy(&c, ats_v3(x.x + e, x.y, x.z), mass, inv_h2) -
                      ats_contact_energy(&c, ats_v3(x.x - e, x.y, x.z), mass, inv_h2)) /
                     (2 * e);
  CHECK(g.x == Approx(fd_x).epsilon(1e-2));
  CHECK(ats_contact_energy(&c, ats_v3(0.0f, 0.56f, 0.0f), mass, inv_h2) == 0.0f);
}

TEST_CASE("the contact summary counts touching pairs, the smallest gap and the deepest penetration") {
  scene::ColliderDesc plane;
  plane.shape = scene::ColliderShape::plane;
  plane.thickness = 0.01;
  const std::vector<ats_collider_c> c = solver::collider_records(model::make_colliders({plane}));
  const std::vector<float> xyz{0, 0.01f, 0, 0, 0.5f, 0, 0, 0.004f, 0};
  const solver::ContactSummary s = solver::summarize_contacts(c, xyz);
  CHECK(s.active == 2);
  CHECK(s.min_distance == Approx(-0.006).margin(1e-6));
  CHECK(s.max_penetration == Approx(0.006).margin(1e-6));
  CHECK(std::isnan(solver::summarize_contacts({}, xyz).min_distance));
}

TEST_CASE("a collider's clear test never claims a point its distance puts within reach") {
  // ats_collider_clear may skip the distance only where the gap is positive
  // (the callers' results are then those the gap gives); it should also
  // claim most points a little past the reach, or it saves nothing.
  scene::ColliderDesc sphere;
  sphere.shape = scene::ColliderShape::sphere;
  sphere.point = {0.2, 0.5, -0.1};
  sphere.radius = 0.3;
  sphere.thickness = 0.004;
  scene::ColliderDesc capsule;
  capsule.shape = scene::ColliderShape::capsule;
  capsule.point = {-0.09, 0.85, 0};
  capsule.end = {-0.12, 0.05, 0};
  capsule.radius = 0.07;
  capsule.thickness = 0.002;
  scene::ColliderDesc thin = capsule;  // long and thin: cancellation near the axis
  thin.point = {-5, 0, 0};
  thin.end = {5, 0.01, 0};
  thin.radius = 0.001;
  thin.thickness = 0.0005;
  for (const scene::ColliderDesc& d : {sphere, capsule, thin}) {
    const ats_collider_c c = record(d);
    const double reach = d.radius + d.thickness;
    std::uint32_t seed = 12345;
    const auto uniform = [&seed] {
      seed = seed * 1664525u + 1013904223u;
      return (seed >> 8) / double(1u << 24);
    };
    int claimed = 0, wrong = 0, far = 0;
    for (int k = 0; k < 200000; ++k) {
      // a point near the surface: a random point, then moved along the
      // gap's normal to a gap in [-2, 2] reach, some within 1e-4 of it
      ats_vec3 x = ats_v3(float(d.point[0] + 12 * (uniform() - 0.5) * (&d == &thin ? 1 : 0.1)),
                          float(d.point[1] + (uniform() - 0.5)), float(d.point[2] + (uniform() - 0.5)));
      const ats_surface_distance s = ats_collider_gap(&c, x);
      const double want = (uniform() < 0.2 ? 1e-4 * (uniform() - 0.5) : 4 * (uniform() - 0.5)) * reach;
      x = ats_add(x, ats_scale(s.n, float(want - s.phi)));
      const float phi = ats_collider_gap(&c, x).phi;
      if (ats_collider_clear(&c, x)) {
        ++claimed;
        if (!(phi > 0)) ++wrong;
      } else if (phi > 0.01 * reach) {
        ++far;
      }
    }
    INFO("collider radius " << d.radius << ": " << claimed << " claimed clear, " << far << " past 1 % not claimed");
    CHECK(wrong == 0);
    CHECK(claimed > 50000);
    CHECK(far < claimed / 100);
  }
}
