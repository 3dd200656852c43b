#pragma once
// Host twin of the xpbd_energy kernels: the same float math headers, the
// same output order (energy_output), one float per particle and constraint.
// Tests compare the device against it element by element.
#include <vector>

#include "solver/layout/sim_layout.hpp"

namespace atssim::solver::energy {

std::vector<float> element_energies(const SimLayout& layout, const std::vector<Float4>& predicted, double h);

}  // namespace atssim::solver::energy
