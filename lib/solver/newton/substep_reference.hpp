#pragma once
// What the relative energy error of one substep is measured against (He et
// al. 2025 Fig. 4): from a state, the predicted positions x~, the energy
// E_0 = E(x~) (held above the ground, as every collision task holds it),
// the Newton minimum E*, and the float32 resolution of y on that state.
//   y = (E − E*) / (E_0 − E*);  0: the exact substep, 1: no better than x~.
// `atssim converge` and `run --tolerance` measure with it.
#include <vector>

#include "solver/layout/sim_layout.hpp"
#include "solver/newton/newton_reference.hpp"

namespace atssim::solver::newton {

struct SubstepReference {
  double h = 0.0;
  std::vector<Float4> start;      // x_t, the state's positions
  std::vector<Float4> predicted;  // x~
  double energy_start = 0.0;      // E_0
  NewtonResult newton;            // x*, E* = newton.energy
  // (E(x* rounded to float32) − E*) / (E_0 − E*): the error a method that
  // stores positions in float32 cannot get below. NaN when E_0 ≤ E*.
  double y_floor = 0.0;

  double span() const { return energy_start - newton.energy; }
  // y of `x` (float4 positions after the substep); 0 when E_0 ≤ E* (x~ is
  // already the minimum: nothing to solve).
  double relative_error(const SimLayout& state, const std::vector<Float4>& x) const;
  // E(x) for positions `x` after the substep.
  double energy(const SimLayout& state, const std::vector<Float4>& x) const;
};

// The reference for the substep of length h from `state` (its x, v and
// colliders). Throws atssim::Error (input) as newton_reference does for
// infinitely stiff constraints.
SubstepReference substep_reference(const SimLayout& state, double h);

// The state after the exact substep: x = x*, v = (x* − x_t) / h.
SimLayout exact_step(const SimLayout& state, const SubstepReference& reference);

}  // namespace atssim::solver::newton
