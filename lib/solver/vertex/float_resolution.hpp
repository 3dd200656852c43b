#pragma once
// Whether a vertex-block method (VBD, SOSD, JPGD) can see the inertia of a
// scene in float32. Each vertex solves (M/h² + K) d = f; when the
// stiffness dwarfs the inertia, h² λ_max(M⁻¹K) beyond ~1/ε of float32, the
// inertia term and the gravity in f vanish in the rounding of the elastic
// terms, and the body moves by rounding noise (issue #13: SOSD with density
// 1e-6 kg/m² and stiffness 1e12 fell 0.81 m in 0.167 s where free fall gives
// 0.14 m). Such a scene is refused before it runs.
#include <string_view>

#include "solver/layout/sim_layout.hpp"

namespace atssim::solver::vertex {

// The largest h² λ_max(M⁻¹K) accepted (Gershgorin bound, as the explicit
// stability limit estimates it). Set from the stability matrix
// (scripts/stability_matrix.py, docs/accuracy.md).
inline constexpr double kMaxStiffnessToInertia = 1e300;  // calibrating: off

// h² times the Gershgorin bound on λ_max(M⁻¹K) of the layout.
double stiffness_to_inertia(const SimLayout& layout, double substep_dt);

// Throws atssim::Error (input) naming the ratio, the limit and the substeps
// per frame that would meet it, when stiffness_to_inertia exceeds the limit.
void require_resolvable_inertia(const SimLayout& layout, double substep_dt, int substeps, std::string_view method);

}  // namespace atssim::solver::vertex
