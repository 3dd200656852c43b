#pragma once
// The incremental potential has the term 1/2 alpha^-1 |C|^2 per constraint,
// so it exists only for compliance alpha > 0; XPBD itself accepts alpha = 0
// (a hard constraint), the energy and the Newton reference cannot.
#include "solver/xpbd/xpbd_layout.hpp"

namespace atssim::solver::energy {

// Throws atssim::Error (input) naming the first constraint whose compliance
// is not positive.
void require_finite_stiffness(const xpbd::XpbdLayout& layout);

}  // namespace atssim::solver::energy
