#include "solver/contact/contact_summary.hpp"

#include <algorithm>
#include <limits>

#include "common/collider_distance.h"

namespace atssim::solver {

namespace {

// As the kernels see it, except that a mesh is searched without a reach, so
// that the smallest distance is the true one however far the mesh is.
float gap_of(const ats_collider_c& c, ats_vec3 x) {
  if (int(c.shape) != ATS_COLLIDER_MESH) return ats_collider_gap(&c, x).phi;
  return ats_mesh_distance(&c, x, std::numeric_limits<float>::max()).phi - c.thickness;
}

}  // namespace

ContactSummary summarize_contacts(const std::vector<ats_collider_c>& colliders, std::span<const float> xyz, int count) {
  ContactSummary s;
  s.min_distance = std::numeric_limits<double>::quiet_NaN();
  if (count < 0) count = static_cast<int>(colliders.size());
  if (count == 0) return s;
  s.min_distance = std::numeric_limits<double>::infinity();
  for (std::size_t i = 0; i + 2 < xyz.size(); i += 3) {
    const ats_vec3 x = ats_v3(xyz[i], xyz[i + 1], xyz[i + 2]);
    for (int k = 0; k < count; ++k) {
      const ats_collider_c& c = colliders[k];
      const float gap = gap_of(c, x);
      s.active += ats_collider_touching(&c, gap);
      s.min_distance = std::min(s.min_distance, double(gap));
      s.max_penetration = std::max(s.max_penetration, double(-gap));
    }
  }
  return s;
}

}  // namespace atssim::solver
