#include "model/tet_geometry.hpp"

#include <algorithm>

#include <Eigen/Geometry>

namespace atssim::model {

double signed_volume(const Vec3& a, const Vec3& b, const Vec3& c, const Vec3& d) {
  return (b - a).cross(c - a).dot(d - a) / 6.0;
}

Eigen::Matrix3d rest_shape_matrix(const Vec3& x0, const Vec3& x1, const Vec3& x2, const Vec3& x3) {
  Eigen::Matrix3d dm;
  dm.col(0) = x1 - x0;
  dm.col(1) = x2 - x0;
  dm.col(2) = x3 - x0;
  return dm;
}

std::vector<std::array<int, 3>> surface_triangles(const std::vector<std::array<int, 4>>& tets) {
  // The four faces of a positive tet (a, b, c, d), each wound to face away from
  // the vertex it omits. Sorting by the sorted corner triple brings the two
  // copies of an interior face together (a sort, as in bending_stencils).
  struct Face {
    std::array<int, 3> key;
    std::array<int, 3> oriented;
  };
  std::vector<Face> faces;
  faces.reserve(tets.size() * 4);
  for (const auto& t : tets) {
    const std::array<std::array<int, 3>, 4> four{
        {{t[0], t[2], t[1]}, {t[0], t[1], t[3]}, {t[0], t[3], t[2]}, {t[1], t[2], t[3]}}};
    for (const auto& f : four) {
      std::array<int, 3> key = f;
      std::sort(key.begin(), key.end());
      faces.push_back({key, f});
    }
  }
  std::sort(faces.begin(), faces.end(), [](const Face& x, const Face& y) { return x.key < y.key; });
  std::vector<std::array<int, 3>> surface;
  for (std::size_t i = 0; i < faces.size();) {
    std::size_t j = i;
    while (j < faces.size() && faces[j].key == faces[i].key) ++j;
    if (j - i == 1) surface.push_back(faces[i].oriented);
    i = j;
  }
  return surface;
}

}  // namespace atssim::model
