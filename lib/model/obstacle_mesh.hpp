#pragma once
// A triangle-mesh obstacle in its local frame (scaled, not yet placed): its
// triangles, whether it is closed (then oriented outward, with the
// pseudo-normals that sign its distance), and the BVH over it
// (kernels/common/mesh_contact.h defines inside and outside).
#include <array>
#include <vector>

#include <Eigen/Core>

#include "model/obstacle_bvh.hpp"

namespace atssim::model {

struct ObstacleMesh {
  std::vector<Eigen::Vector3d> vertices;      // local frame, scaled
  std::vector<std::array<int, 3>> triangles;  // non-degenerate ones; outward for a closed mesh
  bool closed = false;  // every edge shared by exactly two triangles that run it in opposite directions
  std::vector<Eigen::Vector3d> face_normal;                 // per triangle, unit
  std::vector<std::array<Eigen::Vector3d, 3>> edge_normal;  // per triangle: ab, bc, ca (unit)
  std::vector<Eigen::Vector3d> vertex_normal;               // per vertex, angle-weighted (unit)
  ObstacleBvh bvh;
};

// Scales the vertices per axis, drops zero-area triangles, finds whether the
// mesh is closed (and turns it outward if its volume is negative), computes
// the pseudo-normals and builds the BVH.
ObstacleMesh make_obstacle_mesh(const std::vector<std::array<double, 3>>& vertices,
                                const std::vector<std::array<int, 3>>& triangles, const std::array<double, 3>& scale);

}  // namespace atssim::model
