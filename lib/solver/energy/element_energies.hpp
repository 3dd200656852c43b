#pragma once
// Host twin of the xpbd_energy kernels: the same float math headers, the
// same output order (energy_output), one float per particle and constraint.
// Tests compare the device against it element by element.
#include <vector>

#include "solver/xpbd/xpbd_layout.hpp"

namespace atssim::solver::energy {

std::vector<float> element_energies(const xpbd::XpbdLayout& layout, const std::vector<xpbd::Float4>& predicted,
                                    double h);

}  // namespace atssim::solver::energy
