#pragma once
// The contents of a plan's colliders buffer (role colliders): one record per
// collider (common/collider_types.h), then each mesh obstacle's BVH nodes
// and triangles (common/mesh_types.h) packed into further records. Kernels
// take the buffer with the count of records that are colliders.
#include <vector>

#include "common/collider_types.h"
#include "model/collider.hpp"

namespace atssim::solver {

struct ColliderBuffer {
  std::vector<ats_collider_c> records;  // `count` colliders, then the meshes' data
  int count = 0;
};

// The colliders at rest (time 0, no motion).
ColliderBuffer collider_buffer(const std::vector<model::Collider>& colliders);

// One collider's record as placed (its mesh data offsets and near-list
// slots left at 0).
ats_collider_c collider_record(const model::Collider& c);

}  // namespace atssim::solver
