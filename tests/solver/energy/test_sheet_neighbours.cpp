// Sheet neighbours (solver/energy/sheet_neighbours): joined pairs whose
// offset lies within 30 degrees of their triangles' planes, on a small
// hand-built surface whose angles are set by construction.
#include <catch2/catch.hpp>

#include <array>
#include <cmath>
#include <numbers>
#include <vector>

#include <Eigen/Core>

#include "solver/energy/sheet_neighbours.hpp"

using atssim::solver::energy::SheetNeighbours;
using Eigen::Vector3d;

namespace {

// Triangles 0 (0, 1, 2) and 1 (1, 3, 2) share edge (1, 2) in the plane
// z = 0; triangle 2 (0, 4, 1) lies beside triangle 0; triangle 3 (5, 6, 7)
// is apart from them all. `lift` (degrees) turns vertex 3 about edge (1, 2)
// out of the plane: triangle 1 then meets the plane at that angle.
struct Surface {
  std::vector<Vector3d> x;
  std::vector<std::array<int, 3>> tris{{0, 1, 2}, {1, 3, 2}, {0, 4, 1}, {5, 6, 7}};
  SheetNeighbours sheet{tris};

  explicit Surface(double lift = 0.0) {
    const double a = lift * std::numbers::pi / 180.0;
    const Vector3d mid(0.5, 0.5, 0.0), out = Vector3d(1, 1, 0).normalized();
    x = {{0, 0, 0},  {1, 0, 0}, {0, 1, 0}, mid + std::sqrt(0.5) * (std::cos(a) * out + std::sin(a) * Vector3d::UnitZ()),
         {0, -1, 0}, {5, 5, 0}, {6, 5, 0}, {5, 6, 0}};
  }
  SheetNeighbours::Positions at() const {
    return [this](int i) { return x[i]; };
  }
  // Vertex v less the midpoint of edge (1, 2): for vertex 3 lifted by at
  // most 90 degrees, its offset from triangle 0's closest point.
  Vector3d offset_to_edge(int v) const { return x[v] - Vector3d(0.5, 0.5, 0.0); }
};

// A unit vector at `angle` degrees out of the plane z = 0, in the direction d.
Vector3d tilted(const Vector3d& d, double angle) {
  const double a = angle * std::numbers::pi / 180.0;
  return std::cos(a) * d.normalized() + std::sin(a) * Vector3d::UnitZ();
}

}  // namespace

TEST_CASE("a vertex beside a triangle in one flat sheet is a sheet neighbour, and folded off its plane it is not",
          "[contact]") {
  for (const double lift : {0.0, 10.0, 25.0}) {
    const Surface s(lift);
    INFO("lift " << lift);
    CHECK(s.sheet.vertex_triangle(3, s.tris[0], s.offset_to_edge(3), s.at()));
  }
  for (const double lift : {35.0, 60.0, 90.0}) {
    const Surface s(lift);
    INFO("lift " << lift);
    CHECK_FALSE(s.sheet.vertex_triangle(3, s.tris[0], s.offset_to_edge(3), s.at()));
  }
}

TEST_CASE("only joined pairs are sheet neighbours", "[contact]") {
  const Surface s;
  // Vertex 5 is in triangle 0's plane, but no triangle holds it and a corner of triangle 0.
  CHECK_FALSE(s.sheet.vertex_triangle(5, s.tris[0], s.x[5] - s.x[1], s.at()));
  // Vertex 4 shares triangle 2 with corners 0 and 1 of triangle 0, in its plane.
  CHECK(s.sheet.vertex_triangle(4, s.tris[0], s.x[4] - s.x[0], s.at()));
  // Edges (0, 4) and (5, 6) are joined by no triangle.
  CHECK_FALSE(s.sheet.edge_edge({0, 4}, {5, 6}, Vector3d(1, 0, 0), s.at()));
}

TEST_CASE("an edge pair is a sheet neighbour only in the plane of every triangle of both edges", "[contact]") {
  // Edges (1, 2) (triangles 0 and 1) and (0, 4) (triangle 2), joined
  // through vertices 1 and 0 (triangle 0); their offset is along (1, 1, 0).
  const std::array<int, 2> a{1, 2}, b{0, 4};
  const Surface flat;
  CHECK(flat.sheet.edge_edge(a, b, tilted({1, 1, 0}, 0.0), flat.at()));
  CHECK(flat.sheet.edge_edge(b, a, tilted({1, 1, 0}, 20.0), flat.at()));
  CHECK_FALSE(flat.sheet.edge_edge(a, b, tilted({1, 1, 0}, 40.0), flat.at()));
  // Triangle 1 lifted by 45 degrees about edge (1, 2): the offset in the
  // plane z = 0 is 45 degrees off triangle 1's plane.
  const Surface folded(45.0);
  CHECK_FALSE(folded.sheet.edge_edge(a, b, tilted({1, 1, 0}, 0.0), folded.at()));
  CHECK_FALSE(folded.sheet.edge_edge(b, a, tilted({1, 1, 0}, 0.0), folded.at()));
}
