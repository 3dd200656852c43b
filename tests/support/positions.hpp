#pragma once
// Comparing particle arrays in tests.
#include <algorithm>
#include <cmath>
#include <vector>

#include "solver/layout/sim_layout.hpp"

namespace atssim::test {

// The largest coordinate difference between two particle arrays (xyz).
inline double max_distance(const std::vector<solver::Float4>& a, const std::vector<solver::Float4>& b) {
  double worst = 0.0;
  for (std::size_t i = 0; i < a.size(); ++i) {
    worst = std::max({worst, double(std::abs(a[i].x - b[i].x)), double(std::abs(a[i].y - b[i].y)),
                      double(std::abs(a[i].z - b[i].z))});
  }
  return worst;
}

}  // namespace atssim::test
