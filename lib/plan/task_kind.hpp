#pragma once
// What a task of a substep plan does, as a closed set with traits, so that
// the plan transforms, the scheduler's callers and the output ask a trait
// instead of comparing names (DESIGN.md "plan/": task kinds with traits).
// sched::Task::kind holds the enum's value as its label.
#include <string_view>

#include "sched/task_graph.hpp"

namespace atssim::plan {

enum class TaskKind : int {
  predict = 1,      // x_t kept, x~ = x_t + h v + h² g: before the iterations
  stretch,          // a color block of distance constraints (XPBD)
  bend,             // a color block of bending constraints (XPBD)
  tet,              // a color block of tetrahedra (XPBD)
  vertex,           // a vertex color of block-descent steps (VBD)
  jacobi,           // every vertex at once from the same iterate (JPGD)
  systems,          // per-vertex force and Hessian block (SOSD)
  main_block,       // the iteration's main stencil block (SOSD)
  stencils,         // the Jacobi stencil solves of one element kind (SOSD)
  combine,          // the stencils' displacements combined per vertex (SOSD)
  collision,        // contact handling at the end of an iteration
  copy,             // the result moved into the positions
  update_velocity,  // v = (x − x_t) / h: after the iterations
  publish,          // async: a device's positions snapshot for others
  merge,            // async: another device's snapshot merged into this one's copy
  energy,           // per-element terms of the incremental potential
  friction,         // Coulomb friction of the colliders: after the iterations
  detection,        // contact detection between simulated surfaces: before the iterations
};

struct KindTraits {
  std::string_view name;
  // Its blocks form a Gauss-Seidel chain: each reads what the one before
  // wrote. Async Gauss-Seidel keeps the order of such a kind across
  // iterations and ranks it by sched::gauss_seidel_rank (paper §4.1.2).
  bool gauss_seidel = false;
  // Async Gauss-Seidel serializes it at the end of its iteration (paper
  // §4.2.1, "Asyn-Serial Collision").
  bool serial = false;
  // Its launches range over particles (not elements): what it reads and
  // writes is the particle range itself.
  bool per_particle = false;
};

const KindTraits& traits(TaskKind kind);
std::string_view to_string(TaskKind kind);

// The kind of a task of a plan's graph (its label); throws atssim::Error for
// a label that is no TaskKind (a merged task, or a graph from elsewhere).
TaskKind kind_of(const sched::Task& task);

// A task of a plan: its label is the kind.
sched::Task make_task(std::string name, TaskKind kind, int iteration = -1, int block = -1);

}  // namespace atssim::plan
