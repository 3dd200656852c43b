#pragma once
// A bounding volume hierarchy over an obstacle's triangles: built once
// (median split on the longest axis of the centroids), refittable when the
// vertices move. The kernels walk its device copy (kernels/common/
// mesh_contact.h); this is the host side that builds it.
#include <array>
#include <vector>

#include <Eigen/Core>

namespace atssim::model {

struct BvhNode {
  Eigen::Vector3d lo = Eigen::Vector3d::Zero(), hi = Eigen::Vector3d::Zero();
  int first = 0;  // leaf: first entry of `order`; inner: the first of its two adjacent children
  int count = 0;  // leaf: number of triangles (> 0); inner: 0
};

struct ObstacleBvh {
  std::vector<BvhNode> nodes;  // node 0 is the root; children come after their parent
  std::vector<int> order;      // triangle index of each leaf entry
};

// Leaves hold at most `leaf_size` triangles.
ObstacleBvh build_bvh(const std::vector<Eigen::Vector3d>& vertices, const std::vector<std::array<int, 3>>& triangles,
                      int leaf_size = 4);

// Recomputes every node's box for moved vertices, keeping the tree.
void refit_bvh(ObstacleBvh& bvh, const std::vector<Eigen::Vector3d>& vertices,
               const std::vector<std::array<int, 3>>& triangles);

}  // namespace atssim::model
