#include "solver/layout/self_contact_layout.hpp"

#include <algorithm>
#include <map>
#include <numeric>

#include <Eigen/Geometry>

namespace atssim::solver {

namespace {

// Orders ids[lo, hi) so that the implicit tree of the kernels (node j of a
// level has children 2j, 2j + 1) is a median-split tree: the left part of a
// range is the largest power of two below its size, split off along the
// longest axis of the centroids' box.
void order_leaves(std::vector<int>& ids, const std::vector<Eigen::Vector3d>& centroid, int lo, int hi) {
  const int count = hi - lo;
  if (count <= 1) return;
  int left = 1;
  while (left * 2 < count) left *= 2;
  Eigen::AlignedBox3d box;
  for (int i = lo; i < hi; ++i) box.extend(centroid[ids[i]]);
  int axis = 0;
  box.sizes().maxCoeff(&axis);
  std::nth_element(ids.begin() + lo, ids.begin() + lo + left, ids.begin() + hi,
                   [&](int a, int b) { return centroid[a][axis] < centroid[b][axis]; });
  order_leaves(ids, centroid, lo, lo + left);
  order_leaves(ids, centroid, lo + left, hi);
}

// CSR lists of `items` per particle, appended to `out` after its offsets at `at`.
void append_lists(std::vector<int>& out, int at, const std::vector<std::vector<int>>& lists) {
  for (std::size_t i = 0; i < lists.size(); ++i) {
    out[at + i] = static_cast<int>(out.size());
    out.insert(out.end(), lists[i].begin(), lists[i].end());
  }
  out[at + lists.size()] = static_cast<int>(out.size());
}

}  // namespace

SelfContactLayout make_self_contact_layout(const model::Model& model) {
  SelfContactLayout out;
  if (!model.contact_surface || model.contact_surface->triangles.empty()) return out;
  const model::ContactSurface& s = *model.contact_surface;
  const auto& x = model.particles.position;
  const int n = static_cast<int>(x.size());
  out.enabled = true;
  out.thickness = static_cast<float>(s.thickness);
  out.query_radius = static_cast<float>(s.query_radius);
  out.stiffness = static_cast<float>(s.stiffness);
  out.mu_s = static_cast<float>(s.static_friction);
  out.mu_k = static_cast<float>(s.kinetic_friction);

  const int t_count = static_cast<int>(s.triangles.size());
  std::vector<Eigen::Vector3d> centroid(t_count);
  for (int t = 0; t < t_count; ++t)
    centroid[t] = (x[s.triangles[t][0]] + x[s.triangles[t][1]] + x[s.triangles[t][2]]) / 3.0;
  std::vector<int> ids(t_count);
  std::iota(ids.begin(), ids.end(), 0);
  order_leaves(ids, centroid, 0, t_count);

  std::vector<int> vertex_owner(n, -1);
  std::map<std::pair<int, int>, int> edge_id;
  std::vector<std::vector<int>> tris_of(n), edges_of(n);
  double mass = 0.0;
  int free_count = 0;
  for (int leaf = 0; leaf < t_count; ++leaf) {
    const auto& t = s.triangles[ids[leaf]];
    out.tris.push_back({t[0], t[1], t[2], -1});
    std::array<int, 8> owned{-1, -1, -1, -1, -1, -1, -1, -1};
    int vertices = 0, edges = 0;
    for (int k = 0; k < 3; ++k) {
      const int v = t[k];
      tris_of[v].push_back(leaf);
      if (vertex_owner[v] < 0) {
        vertex_owner[v] = leaf;
        owned[vertices++] = v;
        if (model.particles.inv_mass[v] > 0.0) {
          mass += model.particles.mass[v];
          ++free_count;
        }
      }
      const std::pair<int, int> key{std::min(t[k], t[(k + 1) % 3]), std::max(t[k], t[(k + 1) % 3])};
      if (edge_id.emplace(key, static_cast<int>(out.edges.size())).second) {
        owned[4 + edges++] = static_cast<int>(out.edges.size());
        edges_of[key.first].push_back(static_cast<int>(out.edges.size()));
        edges_of[key.second].push_back(static_cast<int>(out.edges.size()));
        out.edges.push_back({key.first, key.second});
      }
    }
    out.leaves.push_back(owned);
  }
  out.contact_mass = free_count > 0 ? static_cast<float>(mass / free_count) : 0.0f;

  out.levels = {0};
  for (int count = t_count;; count = (count + 1) / 2) {
    out.levels.push_back(out.levels.back() + count);
    if (count == 1) break;
  }
  // Per particle the other corners of its triangles, each once: the
  // vertices it is joined to (common/self_contact_bvh.h sc_joined).
  std::vector<std::vector<int>> joined_of(n);
  for (int v = 0; v < n; ++v) {
    for (const int leaf : tris_of[v])
      for (const int c : {out.tris[leaf][0], out.tris[leaf][1], out.tris[leaf][2]})
        if (c != v) joined_of[v].push_back(c);
    std::sort(joined_of[v].begin(), joined_of[v].end());
    joined_of[v].erase(std::unique(joined_of[v].begin(), joined_of[v].end()), joined_of[v].end());
  }
  out.incidence.assign(3 * (n + 1), 0);
  append_lists(out.incidence, 0, tris_of);
  append_lists(out.incidence, n + 1, edges_of);
  append_lists(out.incidence, 2 * (n + 1), joined_of);
  return out;
}

double self_contact_k(const SelfContactLayout& layout, double h) {
  return double(layout.stiffness) * double(layout.contact_mass) / (h * h);
}

}  // namespace atssim::solver
