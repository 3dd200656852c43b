#include "model/collider_pose.hpp"

#include <numbers>

#include <Eigen/Geometry>

namespace atssim::model {

namespace {

Eigen::Vector3d vec(const std::array<double, 3>& v) { return {v[0], v[1], v[2]}; }

RigidPose key_pose(const scene::Keyframe& k) { return {rotation_xyz_deg(k.rotation_deg), vec(k.position)}; }

RigidPose keyframe_pose(const std::vector<scene::Keyframe>& keys, double t) {
  if (t <= keys.front().time) return key_pose(keys.front());
  if (t >= keys.back().time) return key_pose(keys.back());
  std::size_t i = 1;
  while (keys[i].time < t) ++i;
  const scene::Keyframe &a = keys[i - 1], &b = keys[i];
  const double s = (t - a.time) / (b.time - a.time);
  const Eigen::Quaterniond qa(rotation_xyz_deg(a.rotation_deg)), qb(rotation_xyz_deg(b.rotation_deg));
  return {qa.slerp(s, qb).toRotationMatrix(), (1.0 - s) * vec(a.position) + s * vec(b.position)};
}

}  // namespace

Eigen::Matrix3d rotation_xyz_deg(const std::array<double, 3>& deg) {
  const double k = std::numbers::pi / 180.0;
  return (Eigen::AngleAxisd(deg[2] * k, Eigen::Vector3d::UnitZ()) *
          Eigen::AngleAxisd(deg[1] * k, Eigen::Vector3d::UnitY()) *
          Eigen::AngleAxisd(deg[0] * k, Eigen::Vector3d::UnitX()))
      .toRotationMatrix();
}

bool is_kinematic(const Collider& c) { return c.motion.kind != scene::MotionKind::still; }

RigidPose pose_at(const Collider& c, double t) {
  switch (c.motion.kind) {
    case scene::MotionKind::still:
      return {Eigen::Matrix3d::Identity(), c.pivot};
    case scene::MotionKind::velocity: {
      const Eigen::Vector3d w = vec(c.motion.angular_velocity);
      const double angle = w.norm() * t;
      const Eigen::Matrix3d r =
          angle > 0.0 ? Eigen::AngleAxisd(angle, w.normalized()).toRotationMatrix() : Eigen::Matrix3d::Identity();
      return {r, c.pivot + t * vec(c.motion.velocity)};
    }
    case scene::MotionKind::keyframes:
      return keyframe_pose(c.motion.keyframes, t);
  }
  return {};
}

Collider posed(const Collider& c, const RigidPose& pose) {
  Collider out = c;
  const auto place = [&](const Eigen::Vector3d& x) -> Eigen::Vector3d {
    return pose.rotation * (x - c.pivot) + pose.pivot;
  };
  out.point = place(c.point);
  out.end = place(c.end);
  out.normal = pose.rotation * c.normal;
  out.axes = c.axes * pose.rotation.transpose();  // rows: the rotated local axes
  out.pivot = pose.pivot;
  return out;
}

}  // namespace atssim::model
