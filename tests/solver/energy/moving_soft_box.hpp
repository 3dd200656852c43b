#pragma once
// A small soft box (type: solid, 6 tets per cell) hanging from its pinned top
// face, deformed and moving: every free particle displaced by a smooth field
// plus noise and given a swirling velocity. Shared by the energy, Newton and
// device energy tests.
#include <cmath>
#include <random>
#include <string>

#include "model/cloth_builder.hpp"
#include "scene/scene_loader.hpp"
#include "solver/layout/sim_layout.hpp"

namespace atssim::test {

// A 0.2 m box centred on the origin, cells^3 cells, its top face (y = 0.1) pinned.
inline std::string soft_box_yaml(int cells, double youngs_modulus, double poisson_ratio,
                                 const std::string& model = "neo_hookean") {
  const std::string c = std::to_string(cells);
  return "simulation: {fps: 60, substeps: 4, iterations: 8, frames: 1}\n"
         "objects:\n"
         "  - name: box\n"
         "    type: solid\n"
         "    box: {size: [0.2, 0.2, 0.2], resolution: [" +
         c + ", " + c + ", " + c +
         "]}\n"
         "    material: {density: 1000, youngs_modulus: " +
         std::to_string(youngs_modulus) + ", poisson_ratio: " + std::to_string(poisson_ratio) + ", model: " + model +
         "}\n"
         "    pins:\n"
         "      boxes:\n"
         "        - {min: [-1, 0.099, -1], max: [1, 0.101, 1]}\n";
}

// strain: amplitude of the smooth displacement relative to the box size.
inline solver::SimLayout moving_soft_box(int cells, const std::string& model = "neo_hookean", unsigned seed = 1,
                                         double strain = 0.05, double youngs_modulus = 1e4,
                                         double poisson_ratio = 0.3) {
  const auto m =
      model::build_model(scene::parse_scene(soft_box_yaml(cells, youngs_modulus, poisson_ratio, model), "s.yaml", "."));
  solver::SimLayout layout = solver::make_sim_layout(m);
  std::mt19937 rng(seed);
  std::uniform_real_distribution<float> u(-1.0f, 1.0f);
  const float a = static_cast<float>(0.2 * strain);
  const float noise = 0.2f * a;
  for (std::size_t i = 0; i < layout.x.size(); ++i) {
    auto& p = layout.x[i];
    if (p.w == 0.0f) continue;
    const float depth = 0.1f - p.y;  // 0 at the pinned face
    p.x += a * std::sin(10.0f * depth + p.z) + noise * u(rng);
    p.y -= a * depth / 0.2f * (1.0f + std::cos(7.0f * p.x)) + noise * u(rng);
    p.z += a * std::cos(8.0f * p.x) * depth / 0.2f + noise * u(rng);
    layout.v[i] = {0.5f * std::sin(20.0f * p.z), 0.3f * std::cos(15.0f * p.x), 0.4f * std::sin(12.0f * p.y), 0.0f};
  }
  return layout;
}

}  // namespace atssim::test
