#include "solver/energy/element_math.hpp"  // first: the double instance of the shared math

#include <catch2/catch.hpp>

#include <algorithm>
#include <random>

#include <Eigen/Core>

using namespace atssim::solver::energy;

namespace {

using f64::ats_vec3;

ats_vec3 v3(const Eigen::Vector3d& v) { return f64::ats_v3(v.x(), v.y(), v.z()); }

// The smallest distance from p to the triangle, by sampling it densely.
double sampled_point_triangle(const Eigen::Vector3d& p, const Eigen::Vector3d& a, const Eigen::Vector3d& b,
                              const Eigen::Vector3d& c) {
  constexpr int N = 300;
  double best = 1e300;
  for (int i = 0; i <= N; ++i) {
    for (int j = 0; i + j <= N; ++j) {
      const double u = double(i) / N, v = double(j) / N;
      best = std::min(best, (p - (a + u * (b - a) + v * (c - a))).norm());
    }
  }
  return best;
}

double sampled_segments(const Eigen::Vector3d& p0, const Eigen::Vector3d& p1, const Eigen::Vector3d& q0,
                        const Eigen::Vector3d& q1) {
  constexpr int N = 600;
  double best = 1e300;
  for (int i = 0; i <= N; ++i) {
    for (int j = 0; j <= N; ++j) {
      best = std::min(best, ((p0 + (double(i) / N) * (p1 - p0)) - (q0 + (double(j) / N) * (q1 - q0))).norm());
    }
  }
  return best;
}

}  // namespace

TEST_CASE("point-triangle distance matches dense sampling, and its weights rebuild the closest point", "[self]") {
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  const auto rnd = [&] { return Eigen::Vector3d(u(rng), u(rng), u(rng)); };
  for (int k = 0; k < 40; ++k) {
    const Eigen::Vector3d a = rnd(), b = rnd(), c = rnd(), p = rnd();
    const f64::ats_pair_geometry g = f64::ats_point_triangle(v3(p), v3(a), v3(b), v3(c));
    const double sampled = sampled_point_triangle(p, a, b, c);
    CHECK(g.d <= sampled + 1e-12);
    CHECK(g.d == Approx(sampled).margin(1e-2));
    CHECK(g.w[0] == 1.0);
    CHECK(-(g.w[1] + g.w[2] + g.w[3]) == Approx(1.0));
    for (int j = 1; j < 4; ++j) CHECK(g.w[j] <= 1e-15);
  }
}

TEST_CASE("edge-edge distance matches dense sampling", "[self]") {
  std::mt19937 rng(11);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  const auto rnd = [&] { return Eigen::Vector3d(u(rng), u(rng), u(rng)); };
  for (int k = 0; k < 30; ++k) {
    const Eigen::Vector3d p0 = rnd(), p1 = rnd(), q0 = rnd(), q1 = rnd();
    const f64::ats_pair_geometry g = f64::ats_edge_edge(v3(p0), v3(p1), v3(q0), v3(q1));
    const double sampled = sampled_segments(p0, p1, q0, q1);
    CHECK(g.d <= sampled + 1e-12);
    CHECK(g.d == Approx(sampled).margin(1e-2));
  }
}

TEST_CASE("the pair energy's gradient is its finite difference", "[self]") {
  const Eigen::Vector3d q[4] = {{0.1, 0.004, 0.2}, {0, 0, 0}, {1, 0, 0}, {0, 0.001, 1}};
  const double k = 50.0, r = 0.01;
  const auto energy = [&](const Eigen::Vector3d* x) {
    return f64::ats_pair_energy(f64::ats_point_triangle(v3(x[0]), v3(x[1]), v3(x[2]), v3(x[3])), k, r);
  };
  const f64::ats_pair_geometry g = f64::ats_point_triangle(v3(q[0]), v3(q[1]), v3(q[2]), v3(q[3]));
  REQUIRE(g.d < r);
  for (int j = 0; j < 4; ++j) {
    const f64::ats_vec3 grad = f64::ats_pair_gradient(g, k, r, j);
    const double analytic[3] = {grad.x, grad.y, grad.z};
    for (int c = 0; c < 3; ++c) {
      Eigen::Vector3d plus[4] = {q[0], q[1], q[2], q[3]}, minus[4] = {q[0], q[1], q[2], q[3]};
      const double h = 1e-7;
      plus[j][c] += h;
      minus[j][c] -= h;
      CHECK(analytic[c] == Approx((energy(plus) - energy(minus)) / (2 * h)).margin(1e-6));
    }
  }
  // No energy, no force beyond the thickness.
  const f64::ats_pair_geometry far = f64::ats_point_triangle(f64::ats_v3(0.1, 0.02, 0.2), v3(q[1]), v3(q[2]), v3(q[3]));
  CHECK(f64::ats_pair_energy(far, k, r) == 0.0);
}
