#pragma once
// The device layout of a Model that every method reads: float4 particle
// arrays (w = inverse mass) and element arrays ordered by color block.
// Shared by the OpenCL plans and the host references, so both sweep the
// same order.
#include <vector>

#include "common/collider_types.h"
#include "common/element_types.h"
#include "graph/color_blocks.hpp"
#include "model/model.hpp"
#include "solver/layout/self_contact_layout.hpp"

namespace atssim::solver {

struct alignas(16) Float4 {
  float x = 0.0f, y = 0.0f, z = 0.0f, w = 0.0f;
};

struct SimLayout {
  std::vector<Float4> x;                // positions, w = inverse mass
  std::vector<Float4> v;                // velocities, w unused
  std::vector<ats_distance_c> stretch;  // grouped by color
  std::vector<int> stretch_blocks;      // offsets, blocks + 1 entries (empty = none)
  std::vector<ats_bend_c> bend;
  std::vector<int> bend_blocks;
  std::vector<ats_tet_c> tets;  // solids (XPBD accepts StVK ones only)
  std::vector<int> tet_blocks;  // color offsets of `tets` (tets are grouped by color)
  Float4 gravity;
  bool has_ground = false;  // a ground plane y = ground_y (collision task after each iteration)
  float ground_y = 0.0f;
  float air_drag = 0.0f;  // c in 1/s: force −m·c·v on every free particle
  // Per particle: its material's Coulomb mu_s, mu_k (`material.friction`);
  // -1: unset (a collider's own, or contact.friction, then decide).
  std::vector<std::array<float, 2>> friction;
  std::vector<ats_collider_c> colliders;  // collider records, then mesh data (solver/contact/collider_buffer)
  int collider_count = 0;                 // records that are colliders (contact tasks only when > 0)
  SelfContactLayout self_contact;         // contact between simulated surfaces (tasks only when enabled)
};

SimLayout make_sim_layout(const model::Model& model);

// Air drag −m c v at the end-of-substep velocity (implicit) is the term
// ½ (m c/h) |x − x_t|² of the incremental potential; with the inertia term
// it makes ½ m (1 + c h)/h² |x − x̂|² + const, x̂ = x_t + h (v + h g)/(1 + c h).
// So every method predicts with its velocity damped by 1/(1 + c h) and
// weighs the inertia as for a step h/√(1 + c h); the velocity update keeps h.
float velocity_damping(const SimLayout& layout, double h);  // 1/(1 + c h), 1 without drag
double inertia_dt(const SimLayout& layout, double h);       // h/√(1 + c h), h without drag
// Whether some spring has material damping (ats_distance_c::damping > 0).
bool has_spring_damping(const SimLayout& layout);
// The device records of the model's colliders (common/collider_types.h),
// followed by their meshes' data.
std::vector<ats_collider_c> collider_records(const std::vector<model::Collider>& colliders);

}  // namespace atssim::solver
