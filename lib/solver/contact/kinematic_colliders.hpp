#pragma once
// The colliders buffer of a scene whose colliders move: before each substep
// the host poses every collider at the substep's end time and records how
// its surface moved over the substep (friction acts relative to it), then
// writes the buffer (the fused executor launches once per substep, so the
// buffer is never written while a task reads it). Meshes move by their
// placement (c, axes) alone: their BVH stays in the local frame.
#include <vector>

#include "solver/contact/collider_buffer.hpp"

namespace atssim::solver {

class KinematicColliders {
 public:
  KinematicColliders() = default;
  explicit KinematicColliders(std::vector<model::Collider> colliders);

  // Whether any collider moves (else the buffer never changes).
  bool moving() const { return moving_; }
  int count() const { return buffer_.count; }

  // The buffer for the substep from t0 to t1: every collider at its pose at
  // t1, with move/turn/pivot its rigid motion from t0 to t1.
  const std::vector<ats_collider_c>& records(double t0, double t1);
  // The buffer as it was last posed (at rest before the first call).
  const std::vector<ats_collider_c>& current() const { return buffer_.records; }

 private:
  std::vector<model::Collider> colliders_;
  ColliderBuffer buffer_;
  bool moving_ = false;
};

}  // namespace atssim::solver
