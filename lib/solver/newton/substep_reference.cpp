#include "solver/newton/substep_reference.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

#include "solver/energy/incremental_potential.hpp"
#include "solver/energy/predicted_positions.hpp"

namespace atssim::solver::newton {

double SubstepReference::energy(const SimLayout& state, const std::vector<Float4>& x) const {
  SimLayout after = state;
  after.x = x;
  return energy::incremental_potential(after, predicted, h, &start);
}

double SubstepReference::relative_error(const SimLayout& state, const std::vector<Float4>& x) const {
  const double s = span();
  return s > 0.0 ? (energy(state, x) - newton.energy) / s : 0.0;
}

SubstepReference substep_reference(const SimLayout& state, double h) {
  SubstepReference r;
  r.h = h;
  r.start = state.x;
  r.predicted = energy::predicted_positions(state, h);
  // E0 at x~, held above the ground as every method's collision task does
  // (a feasible start: E* <= E0 then holds with the ground bound too).
  std::vector<Float4> held = r.predicted;
  if (state.has_ground) {
    for (Float4& p : held) {
      if (p.w > 0.0f) p.y = std::max(p.y, state.ground_y);
    }
  }
  r.energy_start = r.energy(state, held);
  r.newton = newton_reference(state, r.predicted, h);
  std::vector<Float4> rounded = state.x;
  for (std::size_t i = 0; i < rounded.size(); ++i) {
    rounded[i].x = static_cast<float>(r.newton.x[3 * i]);
    rounded[i].y = static_cast<float>(r.newton.x[3 * i + 1]);
    rounded[i].z = static_cast<float>(r.newton.x[3 * i + 2]);
  }
  r.y_floor = r.span() > 0.0 ? std::abs(r.energy(state, rounded) - r.newton.energy) / r.span()
                             : std::numeric_limits<double>::quiet_NaN();
  return r;
}

SimLayout exact_step(const SimLayout& state, const SubstepReference& reference) {
  SimLayout next = state;
  const float inv_h = static_cast<float>(1.0 / reference.h);
  for (std::size_t i = 0; i < next.x.size(); ++i) {
    if (next.x[i].w == 0.0f) continue;
    const Float4 x{static_cast<float>(reference.newton.x[3 * i]), static_cast<float>(reference.newton.x[3 * i + 1]),
                   static_cast<float>(reference.newton.x[3 * i + 2]), next.x[i].w};
    next.v[i] = {(x.x - state.x[i].x) * inv_h, (x.y - state.x[i].y) * inv_h, (x.z - state.x[i].z) * inv_h, next.v[i].w};
    next.x[i] = x;
  }
  return next;
}

}  // namespace atssim::solver::newton
