#include "solver/energy/predicted_positions.hpp"

namespace atssim::solver::energy {

std::vector<Float4> predicted_positions(const SimLayout& layout, double h) {
  // Same float operations in the same order as XpbdReference::predict.
  const float dt = static_cast<float>(h);
  const Float4 g = layout.gravity;
  const float damp = velocity_damping(layout, h);  // air drag (sim_layout.hpp)
  std::vector<Float4> out = layout.x;
  for (std::size_t i = 0; i < out.size(); ++i) {
    Float4& p = out[i];
    if (p.w == 0.0f) continue;
    const float vx = (layout.v[i].x + dt * g.x) * damp;
    const float vy = (layout.v[i].y + dt * g.y) * damp;
    const float vz = (layout.v[i].z + dt * g.z) * damp;
    p.x += dt * vx;
    p.y += dt * vy;
    p.z += dt * vz;
  }
  return out;
}

}  // namespace atssim::solver::energy
