#include "solver/energy/element_math.hpp"  // first: the double instance of the shared math (brute force)

// The per-frame surface record (solver/contact/surface_contacts): the
// crossing predicate on hand-built configurations, and pair counts, depth
// and crossings against a brute force over every pair.
#include <catch2/catch.hpp>

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <random>
#include <vector>

#include <Eigen/Core>

#include "solver/contact/surface_contacts.hpp"

using namespace atssim;
using Eigen::Vector3d;
using solver::segment_crosses_triangle;
using solver::SurfaceContactCheck;
using solver::SurfaceContacts;

namespace {

namespace f64 = solver::energy::f64;

f64::ats_vec3 v3(const Vector3d& p) { return f64::ats_v3(p.x(), p.y(), p.z()); }

std::vector<float> xyz_of(const std::vector<Vector3d>& x) {
  std::vector<float> out;
  for (const Vector3d& p : x) out.insert(out.end(), {float(p.x()), float(p.y()), float(p.z())});
  return out;
}

// The positions as measure() sees them (float).
std::vector<Vector3d> rounded(const std::vector<Vector3d>& x) {
  std::vector<Vector3d> out;
  for (const Vector3d& p : x) out.emplace_back(float(p.x()), float(p.y()), float(p.z()));
  return out;
}

// Every pair, no broad phase: what measure() must find.
SurfaceContacts brute_force(const SurfaceContactCheck& check, const std::vector<Vector3d>& x) {
  const double r = check.thickness();
  SurfaceContacts s;
  double closest = std::numeric_limits<double>::infinity();
  std::vector<bool> on_surface(x.size(), false);
  for (const auto& t : check.triangles())
    for (int v : t) on_surface[v] = true;
  for (std::size_t v = 0; v < x.size(); ++v) {
    if (!on_surface[v]) continue;
    for (const auto& t : check.triangles()) {
      if (int(v) == t[0] || int(v) == t[1] || int(v) == t[2]) continue;
      const double d = f64::ats_point_triangle(v3(x[v]), v3(x[t[0]]), v3(x[t[1]]), v3(x[t[2]])).d;
      if (d < r) ++s.vertex_triangle, closest = std::min(closest, d);
    }
  }
  const auto& edges = check.edges();
  for (std::size_t e = 0; e < edges.size(); ++e) {
    const auto& a = edges[e];
    for (std::size_t f = e + 1; f < edges.size(); ++f) {
      const auto& b = edges[f];
      if (a[0] == b[0] || a[0] == b[1] || a[1] == b[0] || a[1] == b[1]) continue;
      const double d = f64::ats_edge_edge(v3(x[a[0]]), v3(x[a[1]]), v3(x[b[0]]), v3(x[b[1]])).d;
      if (d < r) ++s.edge_edge, closest = std::min(closest, d);
    }
    for (const auto& t : check.triangles()) {
      const bool touches = a[0] == t[0] || a[0] == t[1] || a[0] == t[2] || a[1] == t[0] || a[1] == t[1] || a[1] == t[2];
      if (!touches && segment_crosses_triangle(x[a[0]], x[a[1]], x[t[0]], x[t[1]], x[t[2]])) ++s.crossings;
    }
  }
  s.max_penetration = s.pairs() > 0 ? r - closest : 0.0;
  return s;
}

// Two n x n sheets of side 1 in y = 0 and y = gap, the upper one rippled by
// `noise` (uniform, per vertex): particles [0, n²) and [n², 2n²).
struct TwoSheets {
  std::vector<Vector3d> x;
  std::vector<std::array<int, 3>> tris;
};

TwoSheets two_sheets(int n, double gap, double noise, unsigned seed) {
  TwoSheets s;
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> jitter(-noise, noise);
  for (int layer = 0; layer < 2; ++layer) {
    const int base = layer * n * n;
    for (int i = 0; i < n; ++i) {
      for (int j = 0; j < n; ++j) {
        const double y = layer == 0 ? 0.0 : gap + jitter(rng);
        s.x.emplace_back(double(i) / (n - 1) + (layer ? 0.013 : 0.0), y, double(j) / (n - 1) + (layer ? 0.007 : 0.0));
      }
    }
    for (int i = 0; i + 1 < n; ++i) {
      for (int j = 0; j + 1 < n; ++j) {
        const int a = base + i * n + j, b = a + n, c = b + 1, d = a + 1;
        s.tris.push_back({a, b, c});
        s.tris.push_back({a, c, d});
      }
    }
  }
  return s;
}

void check_against_brute_force(const std::vector<std::array<int, 3>>& tris, const std::vector<Vector3d>& x, double r) {
  const SurfaceContactCheck check(tris, r);
  const SurfaceContacts got = check.measure(xyz_of(x));
  const SurfaceContacts want = brute_force(check, rounded(x));
  INFO("pairs " << got.vertex_triangle << " + " << got.edge_edge << ", brute force " << want.vertex_triangle << " + "
                << want.edge_edge << "; crossings " << got.crossings << " / " << want.crossings);
  CHECK(got.vertex_triangle == want.vertex_triangle);
  CHECK(got.edge_edge == want.edge_edge);
  CHECK(got.crossings == want.crossings);
  CHECK(got.max_penetration == want.max_penetration);
}

}  // namespace

TEST_CASE("a segment crosses a triangle only when it passes through it from one side to the other",
          "[contact][surface_contacts]") {
  const Vector3d a(0, 0, 0), b(1, 0, 0), c(0, 1, 0);
  // An edge piercing the triangle, either way round.
  CHECK(segment_crosses_triangle(Vector3d(0.2, 0.2, -1), Vector3d(0.25, 0.3, 1), a, b, c));
  CHECK(segment_crosses_triangle(Vector3d(0.25, 0.3, 1), Vector3d(0.2, 0.2, -1), a, b, c));
  CHECK(segment_crosses_triangle(Vector3d(0.2, 0.2, -1), Vector3d(0.2, 0.2, 1), c, b, a));  // the other winding
  // Through the plane outside the triangle, beside its long edge.
  CHECK_FALSE(segment_crosses_triangle(Vector3d(0.6, 0.6, -1), Vector3d(0.6, 0.6, 1), a, b, c));
  // Short of the plane, ending on it (touching), lying in it.
  CHECK_FALSE(segment_crosses_triangle(Vector3d(0.2, 0.2, 0.1), Vector3d(0.2, 0.2, 1), a, b, c));
  CHECK_FALSE(segment_crosses_triangle(Vector3d(0.2, 0.2, 0.0), Vector3d(0.2, 0.2, 1), a, b, c));
  CHECK_FALSE(segment_crosses_triangle(Vector3d(-1, 0.2, 0), Vector3d(2, 0.2, 0), a, b, c));
  // Through a point of its border: counts (the border belongs to it).
  CHECK(segment_crosses_triangle(Vector3d(0.5, 0.0, -1), Vector3d(0.5, 0.0, 1), a, b, c));
  // A degenerate triangle has no side to cross to.
  CHECK_FALSE(segment_crosses_triangle(Vector3d(0.5, 0, -1), Vector3d(0.5, 0, 1), a, b, Vector3d(2, 0, 0)));
}

TEST_CASE("two triangles that cross give two edge-triangle crossings, apart or touching at a vertex none",
          "[contact][surface_contacts]") {
  const double r = 0.01;
  // A in z = 0; B's two edges from its low corner pierce A inside: the
  // intersection segment has one end on each, so two crossings.
  std::vector<Vector3d> x = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0.2, 0.2, -0.5}, {0.25, 0.25, 0.5}, {0.3, 0.1, 0.5}};
  const std::vector<std::array<int, 3>> two = {{0, 1, 2}, {3, 4, 5}};
  SurfaceContactCheck check(two, r);
  SurfaceContacts s = check.measure(xyz_of(x));
  CHECK(s.crossings == 2);
  // One of B's edges through A, the other through A's plane outside it: the
  // intersection leaves A through its edge 1-2, which pierces B.
  x[5] = Vector3d(1.5, 1.5, 0.5);
  s = check.measure(xyz_of(x));
  CHECK(s.crossings == 2);
  // B lifted clear of A: nothing.
  for (int k = 3; k < 6; ++k) x[k].z() += 1.0;
  s = check.measure(xyz_of(x));
  CHECK(s.crossings == 0);
  CHECK(s.pairs() == 0);
  CHECK(s.max_penetration == 0.0);

  // Sharing vertex 0, B standing up out of A's plane: they touch at the
  // shared vertex only. No crossing and no pair (every pair within r of
  // each other is incident).
  const std::vector<Vector3d> y = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {-0.5, -0.5, 0.5}, {-0.2, -0.6, 0.6}};
  const SurfaceContactCheck shared({{0, 1, 2}, {0, 3, 4}}, r);
  s = shared.measure(xyz_of(y));
  CHECK(s.crossings == 0);
  CHECK(s.pairs() == 0);
  // Folded through each other about the shared vertex (B in the plane
  // x = y): their intersection runs from the shared vertex to where B's far
  // edge 3-4 pierces A, so that edge is the one crossing; B's edges from
  // vertex 0 touch A and do not count.
  const std::vector<Vector3d> z = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0.3, 0.3, -0.5}, {0.3, 0.3, 0.5}};
  s = shared.measure(xyz_of(z));
  CHECK(s.crossings == 1);

  // Two separate particles at one position (touching corners, not shared):
  // no crossing, but pairs at distance 0: each corner against the other
  // triangle, and each of A's two edges from it against each of B's.
  const std::vector<Vector3d> w = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0, 0, 0}, {-1, 0, 0.5}, {0, -1, 0.5}};
  s = check.measure(xyz_of(w));
  CHECK(s.crossings == 0);
  CHECK(s.vertex_triangle == 2);
  CHECK(s.edge_edge == 4);
  CHECK(s.max_penetration == r);
}

TEST_CASE("a vertex above a triangle within the thickness is one pair, as deep as the thickness less its height",
          "[contact][surface_contacts]") {
  const double r = 0.01;
  const std::vector<Vector3d> x = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0.2, 0.2, 0.004}, {3, 3, 3}, {3, 4, 3}};
  const SurfaceContactCheck check({{0, 1, 2}, {3, 4, 5}}, r);
  const SurfaceContacts s = check.measure(xyz_of(x));
  CHECK(s.vertex_triangle == 1);
  CHECK(s.edge_edge == 0);
  CHECK(s.max_penetration == Approx(r - 0.004).epsilon(1e-5));  // float positions
  CHECK(s.crossings == 0);
}

TEST_CASE("pair counts, depth and crossings equal a brute force over every pair", "[contact][surface_contacts]") {
  const double r = 0.02;
  SECTION("two sheets a thickness apart, rippled: pairs, no crossings") {
    const TwoSheets s = two_sheets(14, 1.2 * r, 0.6 * r, 3);
    check_against_brute_force(s.tris, s.x, r);
  }
  SECTION("two sheets rippled through each other: pairs and crossings") {
    const TwoSheets s = two_sheets(14, 0.3 * r, 2.0 * r, 5);
    const SurfaceContactCheck check(s.tris, r);
    const SurfaceContacts brute = brute_force(check, rounded(s.x));
    REQUIRE(brute.crossings > 0);  // the configuration tests what it should
    check_against_brute_force(s.tris, s.x, r);
  }
  SECTION("with a stretched triangle, a far vertex and a non-finite one") {
    TwoSheets s = two_sheets(12, 0.3 * r, 2.0 * r, 9);
    s.x[5] = Vector3d(0.4, 3.0, 0.4);  // its triangles reach far up: longer than any cell
    s.x[200] = Vector3d(1e5, 1e5, 1e5);
    s.x[201] = Vector3d(std::numeric_limits<double>::quiet_NaN(), 0, 0);
    check_against_brute_force(s.tris, s.x, r);
  }
}

TEST_CASE("a state with fewer particles than the surface names is a logic error", "[contact][surface_contacts]") {
  const SurfaceContactCheck check({{0, 1, 2}}, 0.01);
  CHECK_THROWS_AS(check.measure(std::vector<float>(6, 0.0f)), std::logic_error);
}
