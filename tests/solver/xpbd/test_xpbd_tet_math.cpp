// The strain constraints of common/xpbd_tet.h in double, against the StVK
// energy of common/energy_tet_stvk.h and against finite differences. A file
// of its own: the headers take one scalar type per translation unit.
#include <math.h>

#include <catch2/catch.hpp>

#include <cmath>
#include <random>

namespace f64 {
#define ats_real double
#include "common/xpbd_tet.h"
#undef ats_real
}  // namespace f64

using namespace f64;

namespace {

struct Tet {
  ats_vec3 x[4];
  ats_mat3 dm_inv;
  double volume;
};

// A random well-shaped rest tet and a random affine deformation of it
// (stretch, shear and rotation of order `strain`), shifted.
Tet random_tet(std::mt19937& rng, double strain) {
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  ats_vec3 rest[4] = {ats_v3(0, 0, 0), ats_v3(1, 0, 0), ats_v3(0, 1, 0), ats_v3(0, 0, 1)};
  for (auto& p : rest) p = ats_add(p, ats_v3(0.2 * u(rng), 0.2 * u(rng), 0.2 * u(rng)));
  const ats_tet_rest r = ats_tet_rest_of(rest);
  Tet t;
  t.dm_inv = r.dm_inv;
  t.volume = std::abs(r.volume);
  ats_mat3 a = ats_m3_diag(1);
  for (int i = 0; i < 3; ++i) a.r[i] = ats_add(a.r[i], ats_v3(strain * u(rng), strain * u(rng), strain * u(rng)));
  const ats_vec3 shift = ats_v3(0.3 + 0.05 * u(rng), -0.2 + 0.05 * u(rng), 0.05 * u(rng));
  for (int k = 0; k < 4; ++k) t.x[k] = ats_add(ats_m3_mul_v(a, rest[k]), shift);
  return t;
}

double constraint(const Tet& t, const ats_vec3* x, int c) {
  return ats_tet_strain_value(ats_tet_green_strain(ats_tet_deformation(x, t.dm_inv)), c);
}

double component(ats_vec3 v, int i) { return i == 0 ? v.x : (i == 1 ? v.y : v.z); }

void nudge(ats_vec3& v, int i, double d) { (i == 0 ? v.x : (i == 1 ? v.y : v.z)) += d; }

}  // namespace

TEST_CASE("the seven strain constraints' 1/2 k C^2 sum is the StVK tet energy", "[xpbd][tet]") {
  std::mt19937 rng(7);
  const double strain = GENERATE(0.01, 0.3, 0.8);
  for (int n = 0; n < 50; ++n) {
    const Tet t = random_tet(rng, strain);
    const double mu = 1.0e3 * (1.0 + n), lambda = 4.0e3 * (1.0 + 0.5 * n);
    const double ours = ats_tet_strain_energy(t.x, t.dm_inv, t.volume, mu, lambda);
    const double stvk = ats_tet_stvk_energy(t.x, t.dm_inv, t.volume, mu, lambda);
    INFO("strain " << strain << " tet " << n << ": " << ours << " vs " << stvk);
    REQUIRE(stvk > 0.0);
    CHECK(ours == Approx(stvk).epsilon(1e-5));
  }
}

TEST_CASE("the strain constraint gradients match central finite differences of C", "[xpbd][tet]") {
  std::mt19937 rng(11);
  const double h = 1e-6;
  double worst = 0.0;
  for (int n = 0; n < 20; ++n) {
    const Tet t = random_tet(rng, 0.4);
    const ats_mat3 f = ats_tet_deformation(t.x, t.dm_inv);
    for (int c = 0; c < ATS_TET_STRAIN_CONSTRAINTS; ++c) {
      for (int a = 0; a < 4; ++a) {
        const ats_vec3 g = ats_tet_strain_gradient(f, t.dm_inv, c, a);
        for (int i = 0; i < 3; ++i) {
          ats_vec3 xp[4], xm[4];
          for (int k = 0; k < 4; ++k) xp[k] = xm[k] = t.x[k];
          nudge(xp[a], i, h);
          nudge(xm[a], i, -h);
          const double fd = (constraint(t, xp, c) - constraint(t, xm, c)) / (2 * h);
          INFO("tet " << n << " constraint " << c << " vertex " << a << " axis " << i);
          CHECK(component(g, i) == Approx(fd).margin(1e-7).epsilon(1e-6));
          worst = std::max(worst, std::abs(component(g, i) - fd));
        }
      }
    }
  }
  INFO("worst |analytic - finite difference| " << worst);
  CHECK(worst < 1e-6);
}

TEST_CASE("sum_c k_c C_c grad C_c is the StVK force V P b_a", "[xpbd][tet]") {
  // The XPBD fixed point (lambda_c = -k_c C_c h^2) then balances exactly the
  // StVK elastic force.
  std::mt19937 rng(3);
  for (int n = 0; n < 20; ++n) {
    const Tet t = random_tet(rng, 0.5);
    const double mu = 2.0e4, lambda = 7.0e4;
    const ats_mat3 f = ats_tet_deformation(t.x, t.dm_inv);
    const ats_mat3 e = ats_tet_green_strain(f);
    for (int a = 0; a < 4; ++a) {
      ats_vec3 sum = ats_v3(0, 0, 0);
      for (int c = 0; c < ATS_TET_STRAIN_CONSTRAINTS; ++c) {
        const double kc = ats_tet_strain_stiffness(c, t.volume, mu, lambda) * ats_tet_strain_value(e, c);
        sum = ats_add(sum, ats_scale(ats_tet_strain_gradient(f, t.dm_inv, c, a), kc));
      }
      const ats_vec3 g = ats_tet_stvk_gradient(t.x, t.dm_inv, t.volume, mu, lambda, a);
      const double scale = std::max(1.0, ats_length(g));
      CHECK(ats_length(ats_sub(sum, g)) < 1e-9 * scale);
    }
  }
}

TEST_CASE("a tet at rest, or moved rigidly, satisfies every strain constraint", "[xpbd][tet]") {
  std::mt19937 rng(5);
  const Tet t = random_tet(rng, 0.0);  // a translated rest shape
  // rotate it by 40 degrees about z
  const double c = std::cos(0.7), s = std::sin(0.7);
  ats_mat3 r = ats_m3_diag(1);
  r.r[0] = ats_v3(c, -s, 0);
  r.r[1] = ats_v3(s, c, 0);
  ats_vec3 xr[4];
  for (int k = 0; k < 4; ++k) xr[k] = ats_m3_mul_v(r, t.x[k]);
  for (int k = 0; k < ATS_TET_STRAIN_CONSTRAINTS; ++k) {
    CHECK(std::abs(constraint(t, t.x, k)) < 1e-12);
    CHECK(std::abs(constraint(t, xr, k)) < 1e-12);
  }
}

TEST_CASE("one XPBD pass with k -> infinity removes a small strain of a free tet", "[xpbd][tet]") {
  // Huge stiffness makes alpha~ ~ 0: each linearised projection is exact to
  // first order, so a few passes take a 1 % strain to rounding level.
  std::mt19937 rng(9);
  Tet t = random_tet(rng, 0.01);
  const double w[4] = {1.0, 2.0, 0.5, 1.0};
  double lam[ATS_TET_LAMBDA_STRIDE] = {};
  const double before = ats_tet_strain_energy(t.x, t.dm_inv, t.volume, 1.0, 1.0);
  for (int pass = 0; pass < 20; ++pass) ats_xpbd_tet(t.x, w, t.dm_inv, t.volume, 1e12, 1e12, lam, 1e-2);
  const double after = ats_tet_strain_energy(t.x, t.dm_inv, t.volume, 1.0, 1.0);
  INFO("energy at mu = lambda = 1: " << before << " -> " << after);
  REQUIRE(before > 1e-8);
  CHECK(after < 1e-12 * before);
  CHECK(lam[7] == 0.0);  // the padding slot is never touched
}
