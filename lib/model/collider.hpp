#pragma once
// Colliders of the model (scene `colliders:`), in world coordinates at
// rest (time 0): what the contact tasks of every method keep particles out
// of. A kinematic one moves rigidly about its pivot (model/collider_pose).
#include <memory>
#include <string>
#include <vector>

#include <Eigen/Core>

#include "model/obstacle_mesh.hpp"
#include "scene/collider_desc.hpp"

namespace atssim::model {

struct Collider {
  std::string name;
  scene::ColliderShape shape = scene::ColliderShape::plane;
  Eigen::Vector3d point = Eigen::Vector3d::Zero();    // plane: on it; sphere, box: centre; capsule: end a; mesh: origin
  Eigen::Vector3d normal = Eigen::Vector3d::UnitY();  // plane: unit normal
  Eigen::Vector3d end = Eigen::Vector3d::Zero();      // capsule: end b
  Eigen::Matrix3d axes = Eigen::Matrix3d::Identity();  // box, mesh: rows are its local axes in world coordinates
  Eigen::Vector3d half = Eigen::Vector3d::Ones();      // box: half extents
  double radius = 0.0;
  double thickness = 0.0;
  double static_friction = 0.0, kinetic_friction = 0.0;
  bool friction_set = false;                        // false: the touching object's material friction decides
  double stiffness = 0.0;                           // contact energy stiffness relative to m/h^2
  scene::ColliderMotion motion;                     // still, velocity or keyframes
  Eigen::Vector3d pivot = Eigen::Vector3d::Zero();  // what moves and turns: centre, capsule midpoint, mesh origin
  std::shared_ptr<const ObstacleMesh> mesh;         // mesh: local frame, placed by point and axes
};

// The scene's colliders placed in the world (plane normals normalised, box
// rotations applied).
std::vector<Collider> make_colliders(const std::vector<scene::ColliderDesc>& colliders);

}  // namespace atssim::model
