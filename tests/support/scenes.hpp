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

// A corner-pinned cloth of resolution × resolution above the ground beside a
// soft box lying on it: stretch, bending, tetrahedra and the ground task in
// one substep of `method` (the box is StVK under XPBD, neo-Hookean otherwise).
inline std::string cloth_and_box_yaml(const std::string& method, int resolution) {
  const std::string solid = method == "xpbd" ? "stvk" : "neo_hookean";
  const std::string r = std::to_string(resolution);
  return "simulation: {fps: 60, substeps: 2, iterations: 4, ground: 0.0}\n"
         "objects:\n"
         "  - name: cloth\n"
         "    grid: {size: [1, 1], resolution: [" +
         r + ", " + r +
         "]}\n"
         "    transform: {translate: [0, 0.3, 0]}\n"
         "    material: {density: 0.2, stretch_stiffness: 1.0e3, bend_stiffness: 1.0e-3}\n"
         "    pins: {boxes: [{min: [-0.51, 0.29, -0.51], max: [-0.49, 0.31, -0.49]}]}\n"
         "  - name: box\n"
         "    type: solid\n"
         "    box: {size: [0.2, 0.2, 0.2], resolution: [2, 2, 2]}\n"
         "    transform: {translate: [0.8, 0.09, 0], rotate: [0, 0, 10]}\n"
         "    material: {density: 1000, youngs_modulus: 5.0e4, poisson_ratio: 0.3, model: " +
         solid +
         "}\n"
         "solver: {method: " +
         method + "}\n";
}

}  // namespace atssim::test
