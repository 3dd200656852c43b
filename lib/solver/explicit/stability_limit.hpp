#pragma once
// The largest stable step of explicit integration, estimated before a run:
// Gershgorin's bound on the largest eigenvalue of M⁻¹K from per-particle
// sums of the elements' stiffness blocks, then each integrator's stability
// boundary on the imaginary axis (undamped springs).
#include "solver/explicit/explicit_plan.hpp"
#include "solver/layout/sim_layout.hpp"

namespace atssim::solver::explicit_rk {

// ω²_max ≤ max over free particles i of (1/m_i) Σ_j ‖K_ij‖, with ‖K_ij‖
// bounded per element: springs k (both blocks of the pair), isometric
// bending k s |K_i||K_j|, dihedral bending 2 k_d |∇θ_i||∇θ_j| at the current
// positions, tetrahedra V (λ + 2μ) |g_i||g_j| (g = rest shape-function
// gradients, linear elasticity). Returns ω²_max in 1/s².
double largest_eigenvalue_bound(const SimLayout& layout);

// h_max for an integrator: semi-implicit Euler 2/ω (its exact boundary),
// RK4 2√2/ω (its boundary on the imaginary axis); explicit midpoint has none
// for undamped springs (|R(iωh)|² = 1 + (ωh)⁴/4), so its limit is where the
// amplitude grows by at most 1e-4 per step, ωh = (8e-4)^¼. Infinite without
// elements.
double stable_step(Integrator integrator, double largest_eigenvalue);

// With damping: the worst mode z'' = -w² z - g z' with w² = largest_eigenvalue
// and g = drag + beta w² (air drag c in 1/s plus the largest spring damping
// beta in s, Rayleigh C = c M + beta K bounds every mode's rate by that g):
// the largest h for which the integrator's 2x2 step matrix has spectral
// radius ≤ 1 (midpoint: ≤ 1 + 1e-4, as undamped), found by a scan and
// bisection. Equals stable_step(integrator, w²) when drag = beta = 0.
double stable_step(Integrator integrator, double largest_eigenvalue, double drag, double beta);

// The spectral radius of one step of the integrator on that mode (tests).
double step_spectral_radius(Integrator integrator, double w2, double g, double h);

// Throws atssim::Error (input) when h exceeds the stable step, naming the
// limit and the substeps per frame that would meet it.
void require_stable_step(const SimLayout& layout, Integrator integrator, double h, int substeps);

}  // namespace atssim::solver::explicit_rk
