#pragma once
// x~ = x_t + h v_t + h^2 g, the predicted positions of the incremental
// potential (He et al. 2025 §3.1), computed in float exactly as the XPBD
// predict step does (v += h g; x += h v), so XPBD and the energy see the
// same x~. Pinned particles (w = 0) stay where they are.
#include <vector>

#include "solver/layout/sim_layout.hpp"

namespace atssim::solver::energy {

std::vector<Float4> predicted_positions(const SimLayout& layout, double h);

}  // namespace atssim::solver::energy
