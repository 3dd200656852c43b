#pragma once
// How a collider moves (docs/scene-format.md, "Kinematic colliders"): not
// at all, at a constant velocity and angular velocity about its pivot, or
// along keyframes. Plain data, validated by scene/kinematic_reader.
#include <array>
#include <vector>

namespace atssim::scene {

enum class MotionKind { still, velocity, keyframes };

// The pose of a collider at `time`: its pivot at `position` (world), turned
// by `rotation_deg` (about x, then y, then z) from the orientation the scene
// gives it.
struct Keyframe {
  double time = 0.0;
  std::array<double, 3> position{0.0, 0.0, 0.0};
  std::array<double, 3> rotation_deg{0.0, 0.0, 0.0};
  int source_line = 0;
};

struct ColliderMotion {
  MotionKind kind = MotionKind::still;
  std::array<double, 3> velocity{0.0, 0.0, 0.0};          // m/s of the pivot
  std::array<double, 3> angular_velocity{0.0, 0.0, 0.0};  // rad/s about the pivot
  std::vector<Keyframe> keyframes;                        // times increasing; constant after the last
};

}  // namespace atssim::scene
