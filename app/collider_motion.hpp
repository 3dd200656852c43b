#pragma once
// Moves a run's kinematic colliders: before a substep, the plan's colliders
// buffer (role colliders) gets every collider posed at the substep's end,
// with its motion over the substep (solver/contact/kinematic_colliders).
// Written between launches only: the fused executor launches once per
// substep here, and PlanExecutor::write waits for the devices first.
#include "device/plan_executor.hpp"
#include "solver/contact/kinematic_colliders.hpp"

namespace atssim::app {

// Writes the colliders for the substep [t0, t1] when any of them moves;
// nothing otherwise.
void pose_colliders(device::PlanExecutor& executor, solver::KinematicColliders& colliders, double t0, double t1);

}  // namespace atssim::app
