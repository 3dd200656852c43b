#include "model/obstacle_bvh.hpp"

#include <algorithm>
#include <limits>
#include <numeric>

namespace atssim::model {

namespace {

void grow(BvhNode& node, const Eigen::Vector3d& p) {
  node.lo = node.lo.cwiseMin(p);
  node.hi = node.hi.cwiseMax(p);
}

void empty_box(BvhNode& node) {
  node.lo = Eigen::Vector3d::Constant(std::numeric_limits<double>::infinity());
  node.hi = -node.lo;
}

void leaf_box(BvhNode& node, const ObstacleBvh& bvh, const std::vector<Eigen::Vector3d>& v,
              const std::vector<std::array<int, 3>>& tris) {
  empty_box(node);
  for (int k = node.first; k < node.first + node.count; ++k) {
    for (int corner : tris[bvh.order[k]]) grow(node, v[corner]);
  }
}

}  // namespace

ObstacleBvh build_bvh(const std::vector<Eigen::Vector3d>& vertices, const std::vector<std::array<int, 3>>& triangles,
                      int leaf_size) {
  ObstacleBvh bvh;
  const int n = static_cast<int>(triangles.size());
  bvh.order.resize(n);
  std::iota(bvh.order.begin(), bvh.order.end(), 0);
  if (n == 0) return bvh;
  std::vector<Eigen::Vector3d> centroid(n);
  for (int t = 0; t < n; ++t) {
    centroid[t] = (vertices[triangles[t][0]] + vertices[triangles[t][1]] + vertices[triangles[t][2]]) / 3.0;
  }
  struct Range {
    int node, begin, end;
  };
  bvh.nodes.push_back({});
  std::vector<Range> todo{{0, 0, n}};
  while (!todo.empty()) {
    const Range r = todo.back();
    todo.pop_back();
    if (r.end - r.begin <= leaf_size) {
      bvh.nodes[r.node].first = r.begin;
      bvh.nodes[r.node].count = r.end - r.begin;
      continue;
    }
    Eigen::Vector3d lo = centroid[bvh.order[r.begin]], hi = lo;
    for (int k = r.begin; k < r.end; ++k) {
      lo = lo.cwiseMin(centroid[bvh.order[k]]);
      hi = hi.cwiseMax(centroid[bvh.order[k]]);
    }
    int axis = 0;
    (hi - lo).maxCoeff(&axis);
    const int mid = (r.begin + r.end) / 2;
    std::nth_element(bvh.order.begin() + r.begin, bvh.order.begin() + mid, bvh.order.begin() + r.end,
                     [&](int a, int b) { return centroid[a][axis] < centroid[b][axis]; });
    const int left = static_cast<int>(bvh.nodes.size());
    bvh.nodes.push_back({});
    bvh.nodes.push_back({});
    bvh.nodes[r.node].first = left;
    bvh.nodes[r.node].count = 0;
    todo.push_back({left, r.begin, mid});
    todo.push_back({left + 1, mid, r.end});
  }
  refit_bvh(bvh, vertices, triangles);
  return bvh;
}

void refit_bvh(ObstacleBvh& bvh, const std::vector<Eigen::Vector3d>& vertices,
               const std::vector<std::array<int, 3>>& triangles) {
  for (int i = static_cast<int>(bvh.nodes.size()) - 1; i >= 0; --i) {  // children after parents
    BvhNode& node = bvh.nodes[i];
    if (node.count > 0) {
      leaf_box(node, bvh, vertices, triangles);
    } else {
      const BvhNode &a = bvh.nodes[node.first], &b = bvh.nodes[node.first + 1];
      node.lo = a.lo.cwiseMin(b.lo);
      node.hi = a.hi.cwiseMax(b.hi);
    }
  }
}

}  // namespace atssim::model
