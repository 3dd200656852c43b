#pragma once
// The springs of a mass-spring cloth (`material.model: springs`, seed 001):
// structural, shear and bending springs as particle pairs, on a grid or on
// any triangle mesh. Exact rules (docs/scene-format.md, "Mass-spring cloth"):
// - grid (Provot 1995): structural = neighbours along a grid line
//   ((i, k)-(i+1, k), (i, k)-(i, k+1)); shear = both diagonals of every quad;
//   bending = second neighbours along a grid line ((i, k)-(i+2, k),
//   (i, k)-(i, k+2)).
// - triangle mesh: structural = every edge; shear = the two opposite
//   vertices of every interior edge (an edge of exactly two triangles), when
//   they are not already joined by an edge; bending = for every directed
//   edge a->b, the neighbour c of b (c != a) whose edge b->c continues a->b
//   most nearly straight, when the angle between b - a and c - b is at most
//   30° at rest, and a, c are not already joined by a structural or shear
//   spring. Every pair appears once, as (min, max), sorted.
#include <array>
#include <vector>

#include <Eigen/Core>

namespace atssim::model {

struct ClothSprings {
  std::vector<std::array<int, 2>> structural, shear, bend;
};

// Vertex (i, k) has index k * nx + i (make_grid_mesh).
ClothSprings grid_springs(int nx, int nz);

ClothSprings mesh_springs(const std::vector<Eigen::Vector3d>& rest, const std::vector<std::array<int, 3>>& triangles);

}  // namespace atssim::model
