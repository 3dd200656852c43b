#include "model/collider.hpp"

#include <numbers>

#include <Eigen/Geometry>

namespace atssim::model {

namespace {

Eigen::Vector3d vec(const std::array<double, 3>& v) { return {v[0], v[1], v[2]}; }

// About x, then y, then z (as an object's transform.rotate).
Eigen::Matrix3d rotation_xyz_deg(const std::array<double, 3>& deg) {
  const double k = std::numbers::pi / 180.0;
  return (Eigen::AngleAxisd(deg[2] * k, Eigen::Vector3d::UnitZ()) *
          Eigen::AngleAxisd(deg[1] * k, Eigen::Vector3d::UnitY()) *
          Eigen::AngleAxisd(deg[0] * k, Eigen::Vector3d::UnitX()))
      .toRotationMatrix();
}

}  // namespace

std::vector<Collider> make_colliders(const std::vector<scene::ColliderDesc>& colliders) {
  std::vector<Collider> out;
  out.reserve(colliders.size());
  for (const scene::ColliderDesc& d : colliders) {
    Collider c;
    c.name = d.name;
    c.shape = d.shape;
    c.point = vec(d.point);
    c.normal = vec(d.normal).normalized();
    c.end = vec(d.end);
    c.axes = rotation_xyz_deg(d.rotate_deg).transpose();  // columns of R are the local axes
    c.half = 0.5 * vec(d.size);
    c.radius = d.radius;
    c.thickness = d.thickness;
    c.static_friction = d.static_friction;
    c.kinetic_friction = d.kinetic_friction;
    c.stiffness = d.stiffness;
    out.push_back(c);
  }
  return out;
}

}  // namespace atssim::model
