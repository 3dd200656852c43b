#include "solver/contact/kinematic_colliders.hpp"

#include <Eigen/Geometry>

#include "model/collider_pose.hpp"

namespace atssim::solver {

namespace {

void put(float* out, const Eigen::Vector3d& v) {
  for (int k = 0; k < 3; ++k) out[k] = float(v[k]);
  out[3] = 0.0f;
}

}  // namespace

KinematicColliders::KinematicColliders(std::vector<model::Collider> colliders)
    : colliders_(std::move(colliders)), buffer_(collider_buffer(colliders_)) {
  for (const model::Collider& c : colliders_) moving_ = moving_ || model::is_kinematic(c);
  if (moving_) records(0.0, 0.0);  // keyframes may place a collider elsewhere at time 0
}

const std::vector<ats_collider_c>& KinematicColliders::records(double t0, double t1) {
  for (int i = 0; i < buffer_.count; ++i) {
    const model::Collider& c = colliders_[i];
    if (!model::is_kinematic(c)) continue;
    const model::RigidPose from = model::pose_at(c, t0), to = model::pose_at(c, t1);
    ats_collider_c r = collider_record(model::posed(c, to));
    for (int k = 0; k < 3; ++k) r.mesh[k] = buffer_.records[i].mesh[k];  // offsets and closedness stay
    r.mesh[3] = buffer_.records[i].mesh[3];
    r.near_slot = buffer_.records[i].near_slot;
    r.near_slots = buffer_.records[i].near_slots;
    const Eigen::AngleAxisd turn(to.rotation * from.rotation.transpose());
    put(r.move, to.pivot - from.pivot);
    put(r.turn, turn.angle() * turn.axis());
    buffer_.records[i] = r;
  }
  return buffer_.records;
}

}  // namespace atssim::solver
