#pragma once
// The incremental potential has the term 1/2 alpha^-1 |C|^2 per constraint,
// so it exists only for compliance alpha > 0; XPBD itself accepts alpha = 0
// (a hard constraint), the energy and the Newton reference cannot.
#include "solver/layout/sim_layout.hpp"

namespace atssim::solver::energy {

// Throws atssim::Error (input) naming the first constraint whose compliance
// is not positive.
void require_finite_stiffness(const SimLayout& layout);

// Throws atssim::Error (input) naming the first tet whose Lame parameters
// are not mu > 0, lambda >= 0 (finite), whose rest volume is not positive,
// or whose model is neither ATS_TET_NEO_HOOKEAN nor ATS_TET_STVK: outside
// these the tet energies are not bounded below or not defined.
void require_valid_tets(const SimLayout& layout);

}  // namespace atssim::solver::energy
