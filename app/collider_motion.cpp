#include "app/collider_motion.hpp"

#include <cstring>
#include <span>

namespace atssim::app {

void pose_colliders(device::PlanExecutor& executor, solver::KinematicColliders& colliders, double t0, double t1) {
  if (!colliders.moving()) return;
  const plan::BufferId id = executor.plan().find_buffer(plan::BufferRole::colliders);
  if (id < 0) return;
  const std::vector<ats_collider_c>& records = colliders.records(t0, t1);
  executor.write(id, std::as_bytes(std::span(records)));
}

}  // namespace atssim::app
