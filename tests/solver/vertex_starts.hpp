#pragma once
// Start states of the vertex-block methods' device tests (VBD, JPGD, SOSD):
// a moving cloth, over the ground, with dihedral bending and damped
// springs, and a moving neo-Hookean bar (81 vertices: its last batch of 8
// is padded); and a plan's x and v after some substeps on the CPU device.
#include <algorithm>
#include <cmath>
#include <cstring>
#include <string>
#include <vector>

#include "device/device_set.hpp"
#include "device/plan_executor.hpp"
#include "solver/energy/moving_cloth.hpp"
#include "solver/vertex/vertex_plan.hpp"

namespace atssim::test {

inline std::vector<solver::Float4> as_float4(const std::vector<std::byte>& raw) {
  std::vector<solver::Float4> out(raw.size() / sizeof(solver::Float4));
  std::memcpy(out.data(), raw.data(), raw.size());
  return out;
}

// A 0.1 x 0.4 x 0.1 m stable neo-Hookean bar pinned at its top face, moving.
inline solver::SimLayout moving_soft_box() {
  const std::string yaml =
      "objects:\n"
      "  - type: solid\n"
      "    box: {size: [0.1, 0.4, 0.1], resolution: [2, 8, 2]}\n"
      "    material: {density: 1000, youngs_modulus: 1.0e6, poisson_ratio: 0.3}\n"
      "    pins: {boxes: [{min: [-1, 0.19, -1], max: [1, 0.21, 1]}]}\n";
  solver::SimLayout layout = solver::make_sim_layout(model::build_model(scene::parse_scene(yaml, "s.yaml", ".")));
  for (std::size_t i = 0; i < layout.v.size(); ++i) {
    const float t = static_cast<float>(i);
    layout.v[i] = {0.3f * std::sin(t), 0.2f * std::cos(0.7f * t), 0.1f * std::sin(1.3f * t), 0.0f};
  }
  return layout;
}

inline solver::SimLayout with_ground(solver::SimLayout layout) {
  float lowest = layout.x.front().y;
  for (const solver::Float4& p : layout.x) lowest = std::min(lowest, p.y);
  layout.has_ground = true;
  layout.ground_y = lowest + 2e-3f;
  return layout;
}

// "cloth", "cloth over the ground", "cloth, half dihedral, damped springs",
// or (any other name) the neo-Hookean bar; h: the substep.
inline solver::SimLayout vertex_start(const std::string& name, double h) {
  if (name == "cloth") return moving_cloth(16, 1e4, 1e-3, h);
  if (name == "cloth over the ground") return with_ground(moving_cloth(16, 1e4, 1e-3, h));
  if (name == "cloth, half dihedral, damped springs") {
    solver::SimLayout layout = moving_cloth(16, 1e4, 1e-3, h);
    for (std::size_t k = 0; k < layout.bend.size(); k += 2) layout.bend[k].model = ATS_BEND_DIHEDRAL;
    for (std::size_t k = 0; k < layout.stretch.size(); k += 3) layout.stretch[k].damping = 0.05f;
    return layout;
  }
  return moving_soft_box();
}

// x and v after `substeps` of `plan` (ids: its buffers) on the whole CPU device.
inline std::pair<std::vector<solver::Float4>, std::vector<solver::Float4>> run_on_cpu(
    const plan::SubstepPlan& plan, const solver::vertex::VertexBuffers& ids, int substeps) {
  const auto devices = device::DeviceSet::open("cpu");
  device::PlanExecutor exec(devices, plan);
  exec.run_substeps(substeps);
  return {as_float4(exec.read(ids.x)), as_float4(exec.read(ids.v))};
}

// Whether two runs' x and v are the same bits.
inline bool same_bits(const std::pair<std::vector<solver::Float4>, std::vector<solver::Float4>>& a,
                      const std::pair<std::vector<solver::Float4>, std::vector<solver::Float4>>& b) {
  const auto same = [](const std::vector<solver::Float4>& p, const std::vector<solver::Float4>& q) {
    return p.size() == q.size() && std::memcmp(p.data(), q.data(), p.size() * sizeof(solver::Float4)) == 0;
  };
  return same(a.first, b.first) && same(a.second, b.second);
}

}  // namespace atssim::test
