#pragma once
// A hanging cloth that is moving, stretched and bent: a few XPBD substeps
// from a disturbed velocity field. Shared by the energy, Newton and device
// energy tests.
#include <cmath>

#include "model/cloth_builder.hpp"
#include "scene/scene_loader.hpp"
#include "solver/xpbd/xpbd_reference.hpp"
#include "support/scenes.hpp"

namespace atssim::test {

inline solver::SimLayout moving_cloth(int resolution, double stretch_stiffness, double bend_stiffness, double h,
                                      int substeps = 5) {
  const auto m = model::build_model(
      scene::parse_scene(hanging_cloth_yaml(resolution, stretch_stiffness, bend_stiffness), "s.yaml", "."));
  solver::SimLayout start = solver::make_sim_layout(m);
  for (std::size_t i = 0; i < start.v.size(); ++i) {
    if (start.x[i].w == 0.0f) continue;
    const float t = static_cast<float>(i);
    start.v[i] = {0.3f * std::sin(t), 0.2f * std::cos(0.7f * t), 0.1f * std::sin(1.3f * t), 0.0f};
  }
  solver::xpbd::XpbdReference warm(std::move(start), {h, 8});
  for (int s = 0; s < substeps; ++s) warm.substep();
  return warm.state();
}

}  // namespace atssim::test
