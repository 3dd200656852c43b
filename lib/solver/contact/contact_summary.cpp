#include "solver/contact/contact_summary.hpp"

#include <algorithm>
#include <limits>

#include "common/collider_distance.h"

namespace atssim::solver {

ContactSummary summarize_contacts(const std::vector<ats_collider_c>& colliders, std::span<const float> xyz) {
  ContactSummary s;
  s.min_distance = std::numeric_limits<double>::quiet_NaN();
  if (colliders.empty()) return s;
  s.min_distance = std::numeric_limits<double>::infinity();
  for (std::size_t i = 0; i + 2 < xyz.size(); i += 3) {
    const ats_vec3 x = ats_v3(xyz[i], xyz[i + 1], xyz[i + 2]);
    for (const ats_collider_c& c : colliders) {
      const float gap = ats_collider_gap(&c, x).phi;
      s.active += ats_collider_touching(&c, gap);
      s.min_distance = std::min(s.min_distance, double(gap));
      s.max_penetration = std::max(s.max_penetration, double(-gap));
    }
  }
  return s;
}

}  // namespace atssim::solver
