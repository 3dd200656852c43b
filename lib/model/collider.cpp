#include "model/collider.hpp"

#include "model/collider_pose.hpp"

namespace atssim::model {

namespace {

Eigen::Vector3d vec(const std::array<double, 3>& v) { return {v[0], v[1], v[2]}; }

Eigen::Vector3d pivot_of(const Collider& c) {
  return c.shape == scene::ColliderShape::capsule ? Eigen::Vector3d(0.5 * (c.point + c.end)) : c.point;
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
    c.friction_set = d.friction_set;
    c.stiffness = d.stiffness;
    c.motion = d.motion;
    c.pivot = pivot_of(c);
    if (d.shape == scene::ColliderShape::mesh) {
      c.mesh = std::make_shared<const ObstacleMesh>(make_obstacle_mesh(d.mesh_vertices, d.mesh_triangles, d.scale));
    }
    out.push_back(c);
  }
  return out;
}

}  // namespace atssim::model
