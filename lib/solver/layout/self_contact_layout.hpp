#pragma once
// The device layout of contact between simulated surfaces (model
// ContactSurface; kernels/contact/self_contact.cl): the surface triangles in
// the leaf order of a BVH built once here, its edges, which vertices and
// edges each leaf owns (each is owned by one of its triangles, so the
// triangle BVH also finds them), the node levels, and the per-particle
// incidence lists. The BVH is refitted on the device every substep.
//
// Why a BVH refitted from a fixed topology, and not a spatial hash: its
// refit and queries are one pass per element with no atomics and no sort,
// so every detection task is a range of independent elements that `split`
// and `heft` cut, with the same result on any cut (no insertion order).
// Measured against a spatial hash rebuilt per step (bench/bench_broad_phase,
// docs/benchmarks.md): on the host the hash took 4-18 % less time at its best
// cell size; the BVH stays for the property above (docs/architecture.md).
#include <array>
#include <vector>

#include "model/model.hpp"

namespace atssim::solver {

struct SelfContactLayout {
  bool enabled = false;
  float thickness = 0.0f;                 // r of the contact energy (common/self_contact.h)
  float query_radius = 0.0f;              // detection radius at the start of a substep
  float stiffness = 0.0f;                 // relative to m/h²
  float contact_mass = 0.0f;              // m: the mean mass of the free surface particles; k = stiffness m / h²
  float mu_s = 0.0f, mu_k = 0.0f;         // Coulomb friction between the surfaces
  float gamma = 0.4f;                     // VBD's displacement bound: gamma times the distance to the nearest primitive
  std::vector<std::array<int, 4>> tris;   // leaf order; [3] = -1
  std::vector<std::array<int, 2>> edges;  // unique surface edges
  std::vector<std::array<int, 8>> leaves;  // per leaf: owned vertices [0..2], owned edges [4..6] (-1 = none)
  std::vector<int> levels;                 // node offset of each level, then the node count (level 0 = leaves)
  // [0, n]: offsets of incident triangles, [n+1, 2n+1]: of incident edges,
  // [2n+2, 3n+2]: of joined vertices (the other corners of its triangles,
  // each once); then the lists
  std::vector<int> incidence;
  int root() const { return static_cast<int>(levels.size()) - 2; }
  int node_count() const { return levels.empty() ? 0 : levels.back(); }
};

// Empty (enabled false) when the model has no contact surface.
SelfContactLayout make_self_contact_layout(const model::Model& model);

// The contact energy stiffness k = stiffness m / h² for the inertia step h.
double self_contact_k(const SelfContactLayout& layout, double h);

}  // namespace atssim::solver
