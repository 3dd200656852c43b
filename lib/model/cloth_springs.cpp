#include "model/cloth_springs.hpp"

#include <algorithm>
#include <cmath>
#include <set>

#include "model/cloth_builder.hpp"

namespace atssim::model {

namespace {

std::array<int, 2> pair_of(int a, int b) { return {std::min(a, b), std::max(a, b)}; }

void sort_unique(std::vector<std::array<int, 2>>& pairs) {
  std::sort(pairs.begin(), pairs.end());
  pairs.erase(std::unique(pairs.begin(), pairs.end()), pairs.end());
}

// cos 30°: a bending spring continues its edge within 30° of straight.
constexpr double kStraight = 0.86602540378443865;

}  // namespace

ClothSprings grid_springs(int nx, int nz) {
  ClothSprings s;
  const auto at = [nx](int i, int k) { return k * nx + i; };
  for (int k = 0; k < nz; ++k) {
    for (int i = 0; i < nx; ++i) {
      if (i + 1 < nx) s.structural.push_back(pair_of(at(i, k), at(i + 1, k)));
      if (k + 1 < nz) s.structural.push_back(pair_of(at(i, k), at(i, k + 1)));
      if (i + 1 < nx && k + 1 < nz) {
        s.shear.push_back(pair_of(at(i, k), at(i + 1, k + 1)));
        s.shear.push_back(pair_of(at(i + 1, k), at(i, k + 1)));
      }
      if (i + 2 < nx) s.bend.push_back(pair_of(at(i, k), at(i + 2, k)));
      if (k + 2 < nz) s.bend.push_back(pair_of(at(i, k), at(i, k + 2)));
    }
  }
  sort_unique(s.structural);
  sort_unique(s.shear);
  sort_unique(s.bend);
  return s;
}

ClothSprings mesh_springs(const std::vector<Eigen::Vector3d>& rest, const std::vector<std::array<int, 3>>& triangles) {
  ClothSprings s;
  s.structural = unique_edges(triangles);
  const std::set<std::array<int, 2>> edges(s.structural.begin(), s.structural.end());
  for (const auto& st : bending_stencils(triangles)) {
    const auto p = pair_of(st[2], st[3]);
    if (!edges.count(p)) s.shear.push_back(p);
  }
  sort_unique(s.shear);
  const std::set<std::array<int, 2>> shear(s.shear.begin(), s.shear.end());
  std::vector<std::vector<int>> neighbours(rest.size());
  for (const auto& e : s.structural) {
    neighbours[e[0]].push_back(e[1]);
    neighbours[e[1]].push_back(e[0]);
  }
  for (const auto& e : s.structural) {
    for (int dir = 0; dir < 2; ++dir) {
      const int a = e[dir], b = e[1 - dir];
      const Eigen::Vector3d ab = rest[b] - rest[a];
      int best = -1;
      double best_cos = kStraight;
      for (int c : neighbours[b]) {
        if (c == a) continue;
        const Eigen::Vector3d bc = rest[c] - rest[b];
        const double den = ab.norm() * bc.norm();
        if (!(den > 0.0)) continue;
        const double cosine = ab.dot(bc) / den;
        if (cosine >= best_cos) {
          best_cos = cosine;
          best = c;
        }
      }
      if (best < 0 || best == a) continue;
      const auto p = pair_of(a, best);
      if (!edges.count(p) && !shear.count(p)) s.bend.push_back(p);
    }
  }
  sort_unique(s.bend);
  return s;
}

}  // namespace atssim::model
