#pragma once
// Small scenes used across tests.
#include <string>

namespace atssim::test {

// A grid cloth pinned at the two corners of its z = -size/2 edge.
inline std::string hanging_cloth_yaml(int resolution, double stretch_stiffness = 1e4, double bend_stiffness = 1e-3,
                                      int iterations = 8) {
  const std::string r = std::to_string(resolution);
  return "simulation: {fps: 60, substeps: 4, iterations: " + std::to_string(iterations) +
         ", frames: 10}\n"
         "objects:\n"
         "  - name: cloth\n"
         "    grid: {size: [1, 1], resolution: [" +
         r + ", " + r +
         "]}\n"
         "    material: {density: 0.2, stretch_stiffness: " +
         std::to_string(stretch_stiffness) + ", bend_stiffness: " + std::to_string(bend_stiffness) +
         "}\n"
         "    pins:\n"
         "      boxes:\n"
         "        - {min: [-0.51, -0.01, -0.51], max: [-0.49, 0.01, -0.49]}\n"
         "        - {min: [0.49, -0.01, -0.51], max: [0.51, 0.01, -0.49]}\n";
}

// A StVK bar of 0.1 x 0.4 x 0.1 m, `cells` × 4·cells × `cells` cubes of 6
// tets, pinned at its top face (y = 0.2), for XPBD's tet constraints.
inline std::string stvk_bar_yaml(int cells) {
  const std::string c = std::to_string(cells);
  return "simulation: {fps: 60, substeps: 4, iterations: 8, frames: 10}\n"
         "objects:\n"
         "  - name: bar\n"
         "    type: solid\n"
         "    box: {size: [0.1, 0.4, 0.1], resolution: [" +
         c + ", " + std::to_string(4 * cells) + ", " + c +
         "]}\n"
         "    material: {density: 1000, youngs_modulus: 1.0e6, poisson_ratio: 0.3, model: stvk}\n"
         "    pins: {boxes: [{min: [-1, 0.19, -1], max: [1, 0.21, 1]}]}\n";
}

}  // namespace atssim::test
