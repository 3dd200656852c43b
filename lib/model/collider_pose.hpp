#pragma once
// Where a kinematic collider is at a time (scene: velocity/angular_velocity
// or keyframes): a rigid motion about its pivot, x(t) = R(t) (x - pivot) +
// pivot(t), applied to its rest placement.
#include <array>

#include <Eigen/Core>

#include "model/collider.hpp"

namespace atssim::model {

struct RigidPose {
  Eigen::Matrix3d rotation = Eigen::Matrix3d::Identity();  // from the rest orientation
  Eigen::Vector3d pivot = Eigen::Vector3d::Zero();         // where the pivot is
};

// About x, then y, then z, in degrees (as an object's transform.rotate).
Eigen::Matrix3d rotation_xyz_deg(const std::array<double, 3>& deg);

bool is_kinematic(const Collider& c);

// Velocity: pivot + v t, turned by |w| t about w; keyframes: linear in the
// position and spherical-linear in the rotation between the keys around t,
// the first key's pose before it and the last key's after it; still: rest.
RigidPose pose_at(const Collider& c, double t);

// The collider moved to `pose` (its pivot included).
Collider posed(const Collider& c, const RigidPose& pose);

}  // namespace atssim::model
