#include <catch2/catch.hpp>

#include <cmath>
#include <numbers>

#include "model/collider_pose.hpp"

using namespace atssim;
using Eigen::Vector3d;

namespace {

model::Collider box_at(const Vector3d& centre) {
  scene::ColliderDesc d;
  d.shape = scene::ColliderShape::box;
  d.point = {centre.x(), centre.y(), centre.z()};
  d.size = {2.0, 1.0, 1.0};
  return model::make_colliders({d}).front();
}

}  // namespace

TEST_CASE("a collider with a velocity moves its pivot by v t and turns about it by |w| t") {
  model::Collider c = box_at({1, 0, 0});
  c.motion.kind = scene::MotionKind::velocity;
  c.motion.velocity = {0.5, 0, 0};
  c.motion.angular_velocity = {0, std::numbers::pi / 2, 0};  // a quarter turn per second about +y
  const model::RigidPose p = model::pose_at(c, 1.0);
  CHECK((p.pivot - Vector3d(1.5, 0, 0)).norm() < 1e-12);
  // +x turned a quarter about +y is -z.
  CHECK((p.rotation * Vector3d::UnitX() - Vector3d(0, 0, -1)).norm() < 1e-12);
  const model::Collider moved = model::posed(c, p);
  CHECK((moved.point - Vector3d(1.5, 0, 0)).norm() < 1e-12);
  // The box's long local x axis now points along -z in the world.
  CHECK((moved.axes.row(0).transpose() - Vector3d(0, 0, -1)).norm() < 1e-12);
}

TEST_CASE("keyframes interpolate linearly, and hold the first and last pose outside their times") {
  model::Collider c = box_at({0, 0, 0});
  c.motion.kind = scene::MotionKind::keyframes;
  c.motion.keyframes = {{1.0, {0, 0, 0}, {0, 0, 0}, 0}, {3.0, {2, 4, 0}, {0, 0, 90}, 0}};
  CHECK((model::pose_at(c, 0.0).pivot - Vector3d(0, 0, 0)).norm() < 1e-12);
  CHECK((model::pose_at(c, 2.0).pivot - Vector3d(1, 2, 0)).norm() < 1e-12);
  CHECK((model::pose_at(c, 10.0).pivot - Vector3d(2, 4, 0)).norm() < 1e-12);
  // Half-way the rotation is half of 90 degrees about z.
  const Vector3d x = model::pose_at(c, 2.0).rotation * Vector3d::UnitX();
  CHECK(std::abs(std::atan2(x.y(), x.x()) - std::numbers::pi / 4) < 1e-12);
  const Vector3d last = model::pose_at(c, 5.0).rotation * Vector3d::UnitX();
  CHECK((last - Vector3d(0, 1, 0)).norm() < 1e-12);
}

TEST_CASE("a still collider stays where the scene put it") {
  const model::Collider c = box_at({1, 2, 3});
  CHECK_FALSE(model::is_kinematic(c));
  const model::Collider at = model::posed(c, model::pose_at(c, 7.0));
  CHECK((at.point - c.point).norm() == 0.0);
  CHECK((at.axes - c.axes).norm() == 0.0);
}
