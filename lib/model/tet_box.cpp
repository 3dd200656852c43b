#include "model/tet_box.hpp"

#include <algorithm>

#include "model/tet_geometry.hpp"

namespace atssim::model {

scene::TetMesh make_tet_box(const scene::TetBoxDesc& box) {
  const std::array<int, 3> n = box.resolution;
  const int px = n[0] + 1, py = n[1] + 1, pz = n[2] + 1;
  scene::TetMesh mesh;
  mesh.vertices.reserve(static_cast<std::size_t>(px) * py * pz);
  for (int k = 0; k < pz; ++k) {
    for (int j = 0; j < py; ++j) {
      for (int i = 0; i < px; ++i) {
        mesh.vertices.push_back({box.size[0] * (static_cast<double>(i) / n[0] - 0.5),
                                 box.size[1] * (static_cast<double>(j) / n[1] - 0.5),
                                 box.size[2] * (static_cast<double>(k) / n[2] - 0.5)});
      }
    }
  }
  const auto index = [&](int i, int j, int k) { return (k * py + j) * px + i; };
  // The 3! axis orders; a path that is an odd permutation of (x, y, z) gives
  // a negative tet, fixed by swapping its last two vertices.
  std::array<int, 3> order{0, 1, 2};
  std::vector<std::array<int, 3>> orders;
  do {
    orders.push_back(order);
  } while (std::next_permutation(order.begin(), order.end()));

  mesh.tetrahedra.reserve(6 * static_cast<std::size_t>(n[0]) * n[1] * n[2]);
  for (int k = 0; k < n[2]; ++k) {
    for (int j = 0; j < n[1]; ++j) {
      for (int i = 0; i < n[0]; ++i) {
        for (const auto& axes : orders) {
          std::array<int, 3> c{i, j, k};
          std::array<int, 4> tet{index(c[0], c[1], c[2]), 0, 0, 0};
          for (int step = 0; step < 3; ++step) {
            ++c[axes[step]];
            tet[step + 1] = index(c[0], c[1], c[2]);
          }
          const auto p = [&](int v) {
            const auto& x = mesh.vertices[tet[v]];
            return Vec3(x[0], x[1], x[2]);
          };
          if (signed_volume(p(0), p(1), p(2), p(3)) < 0.0) std::swap(tet[2], tet[3]);
          mesh.tetrahedra.push_back(tet);
        }
      }
    }
  }
  return mesh;
}

}  // namespace atssim::model
