#pragma once
// Geometry of linear tetrahedra: signed volume, rest-shape matrix, surface.
#include <array>
#include <vector>

#include "model/model.hpp"

namespace atssim::model {

// det[b−a, c−a, d−a] / 6: positive when d lies on the side that
// (b−a)×(c−a) points to.
double signed_volume(const Vec3& a, const Vec3& b, const Vec3& c, const Vec3& d);

// Dm = [x1−x0, x2−x0, x3−x0] (columns), the rest shape of Sifakis & Barbic 2012 §4.1.
Eigen::Matrix3d rest_shape_matrix(const Vec3& x0, const Vec3& x1, const Vec3& x2, const Vec3& x3);

// The boundary of a tetrahedral mesh: faces used by exactly one tet, ordered
// so that their normal (b−a)×(c−a) points out of it (tets must have positive
// orientation). Faces shared by more than two tets (non-manifold) are not boundary.
std::vector<std::array<int, 3>> surface_triangles(const std::vector<std::array<int, 4>>& tets);

}  // namespace atssim::model
