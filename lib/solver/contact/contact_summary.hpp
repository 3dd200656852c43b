#pragma once
// How the particles touch the analytic colliders in one state, measured with
// the kernels' own distance math (kernels/common/collider_distance.h): what
// the output records per frame (/contact) and what the contact tests check.
#include <span>
#include <vector>

#include "common/collider_types.h"

namespace atssim::solver {

struct ContactSummary {
  int active = 0;              // particle-collider pairs closer than 1 % of the thickness beyond it
  double min_distance = 0.0;   // smallest gap: distance to a surface less its thickness (NaN: no colliders)
  double max_penetration = 0;  // largest depth inside a thickened surface (0: none)
};

// xyz: 3 floats per particle; `colliders` a colliders buffer whose first
// `count` records are colliders (-1: all of them, no mesh data).
ContactSummary summarize_contacts(const std::vector<ats_collider_c>& colliders, std::span<const float> xyz,
                                  int count = -1);

}  // namespace atssim::solver
