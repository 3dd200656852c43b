#pragma once
// What the launches of a plan write, for devices that share no memory
// (plan/write_span.hpp): the particles of each element, as index tables the
// plan's write spans point at, and the spans every method's particle tasks use.
#include <memory>
#include <vector>

#include "plan/write_span.hpp"
#include "solver/layout/sim_layout.hpp"

namespace atssim::solver {

inline constexpr std::uint32_t kParticleBytes = 16;  // a float4 per particle

// Per element, its particles: 2 per stretch constraint, 4 per bending
// stencil or tetrahedron, in layout order.
std::shared_ptr<const std::vector<std::int32_t>> particles_of(const std::vector<ats_distance_c>& stretch);
std::shared_ptr<const std::vector<std::int32_t>> particles_of(const std::vector<ats_bend_c>& bend);
std::shared_ptr<const std::vector<std::int32_t>> particles_of(const std::vector<ats_tet_c>& tets);

// Element e writes particle e of `buffer` (a float4 per particle).
inline plan::WriteSpan particle_write(plan::BufferId buffer) {
  return plan::WriteSpan::per_element(buffer, kParticleBytes);
}

}  // namespace atssim::solver
