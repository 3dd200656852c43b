#pragma once
// The buffers of a substep plan, declared by role so that the executor, the
// output and `converge` find the state without looking a buffer up by name
// (DESIGN.md "plan/": buffers by role).
#include <cstddef>
#include <cstring>
#include <string>
#include <string_view>
#include <vector>

namespace atssim::plan {

using BufferId = int;

enum class BufferRole {
  positions,        // float4 per particle (xyz, w = inverse mass): the state the output reads
  velocities,       // float4 per particle (xyz used): the rest of the state carried between substeps
  start_positions,  // the positions at the start of the substep (for the velocity update)
  inertia_target,   // x~ = x_t + h v + h² g
  elements,         // element arrays (constraints, stencils, tetrahedra); never written
  topology,         // adjacency lists and orderings; never written
  multipliers,      // per-element state that restarts every substep (XPBD's lambdas)
  scratch,          // written before it is read within a substep (iterates, vertex systems, …)
  replica,          // async: another device's copy of the positions
  snapshot,         // async: a published copy of some device's positions
  results,          // what a plan computes for the host to read (energy terms)
  colliders,        // collider records and mesh data; never written by a task, rewritten by the host
                    // between substeps when colliders move (solver/contact/kinematic_colliders)
  cache,            // results kept from one substep to the next (the surface contact pair
                    // lists), valid only while a cache_state buffer says so; remade from the
                    // carried buffers after a reset (PlanState)
  cache_state,      // small state saying whether the caches hold anything: restored to the
                    // plan's initial contents by PlanExecutor::reset() (resume, repeats, probes)
  carried,          // what the caches were made from (the lists' positions and their decision
                    // state): carried with the positions between substeps and frames, read
                    // into PlanState and kept in a checkpoint, so that a restored run remakes
                    // the caches it had, bit for bit
};

std::string_view to_string(BufferRole role);

struct BufferSpec {
  std::string name;  // "x", "v", "stretch", … (for messages and output)
  BufferRole role = BufferRole::scratch;
  std::vector<std::byte> initial;  // initial contents; its size is the buffer's size
};

// The bytes of a vector of plain values, as a buffer's initial contents.
template <typename T>
std::vector<std::byte> bytes_of(const std::vector<T>& values) {
  std::vector<std::byte> out(values.size() * sizeof(T));
  if (!out.empty()) std::memcpy(out.data(), values.data(), out.size());
  return out;
}

// Plain values from a buffer's bytes (the inverse of bytes_of).
template <typename T>
std::vector<T> values_of(const std::vector<std::byte>& bytes) {
  std::vector<T> out(bytes.size() / sizeof(T));
  if (!out.empty()) std::memcpy(out.data(), bytes.data(), out.size() * sizeof(T));
  return out;
}

}  // namespace atssim::plan
