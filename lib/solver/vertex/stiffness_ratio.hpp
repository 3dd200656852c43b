#pragma once
// How stiff a scene is for its step: h² λmax(M⁻¹K), the stiffness of the
// stiffest particle against its inertia m/h² (Gershgorin bound, as the
// explicit stability limit estimates it).
//
// The Jacobi-style methods use it to choose safe defaults: their
// aggressive ones (SOSD's stencil step 0.7, JPGD's Chebyshev acceleration
// at rho 0.9) make the iterations diverge on stiff scenes -- issue #13's
// SOSD cloth of density 1e-6 kg/m² at stiffness 1e12 moved up instead of
// falling -- while step 0.35 and no acceleration keep every cell of the
// sweep in docs/accuracy.md ("The light and stiff SOSD case") falling
// below free fall. The default hanging cloth sits near 2e3; at 1e6 the
// matrix's iteration sweep (5.9e5) still rose, hence 1e5.
#include "solver/layout/sim_layout.hpp"

namespace atssim::solver::vertex {

// Above this h² λmax the Jacobi methods take their safe defaults.
inline constexpr double kStiffForJacobi = 1e5;

// h² times the Gershgorin bound on λmax(M⁻¹K) of the layout.
double stiffness_to_inertia(const SimLayout& layout, double substep_dt);

// Whether the layout is stiff for the Jacobi methods' aggressive defaults.
bool stiff_for_jacobi(const SimLayout& layout, double substep_dt);

}  // namespace atssim::solver::vertex
