#pragma once
// Second-order Stencil Descent (Lan et al. 2023) in the hybrid Jacobi /
// Gauss-Seidel form of the ATS paper (§5) as a substep plan: predict, then
// per iteration the vertex systems, the stencil solves (one task for the
// iteration's main Gauss-Seidel block, one per element kind for the Jacobi
// rest; all read the same x^k, so they run side by side), and the combine
// task in which the main block takes precedence; then the velocity update.
// Every launch is a range over independent items, so `split` cuts them
// between devices exactly.
#include <string_view>

#include "plan/substep_plan.hpp"
#include "plan/task_kind.hpp"
#include "solver/layout/sim_layout.hpp"
#include "solver/vertex/vertex_plan.hpp"

namespace atssim::solver::sosd {

// The embedded program its plans run: kernels/sosd/sosd.cl.
inline constexpr std::string_view kProgram = "sosd";

// SOSD's task kinds (all of one iteration read the same x^k: no chain).
inline constexpr plan::TaskKind kSystems{{"systems", false, false, true}};  // per-vertex force and Hessian block
inline constexpr plan::TaskKind kMainBlock{{"main", false, false, false}};  // the iteration's main stencil block
inline constexpr plan::TaskKind kStencils{
    {"stencils", false, false, false}};  // the Jacobi stencil solves of one element kind
inline constexpr plan::TaskKind kCombine{
    {"combine", false, false, true}};  // the stencils' displacements combined per vertex

// The stencil blocks in the order the main Gauss-Seidel block rotates
// through them: stretch colors, bending colors, tetrahedron colors.
struct StencilBlock {
  int kind = 0;  // 0 stretch, 1 bending, 2 tetrahedron (vertex_layout codes)
  int first = 0;
  int end = 0;
};
std::vector<StencilBlock> stencil_blocks(const SimLayout& layout);

// Iteration `it` (0-based) uses block it mod blocks as its main block. Every
// vertex moves by `step` (solver.stencil_step) times its displacement: the
// main block's stencils share no vertex but do share elements with their
// neighbours, which move in the same step, so a full step is a Jacobi step
// over nearly every vertex (a stretch color is a matching) and overshoots on
// stiff cloth (docs/accuracy.md).
//
// solver.ordering: colors solves a stencil per work-item; color_batches
// cuts each color block of bending stencils into batches of 8 whose
// Cholesky solves run as 8 float lanes (kernels/sosd/sosd.cl
// sosd_bend_lanes), the same bits.
enum class SosdOrdering { colors, color_batches };  // solver.ordering's choices in order
plan::SubstepPlan make_sosd_plan(const SimLayout& layout, double substep_dt, int iterations, double step = 0.7,
                                 vertex::VertexBuffers* ids = nullptr, SosdOrdering ordering = SosdOrdering::colors);

}  // namespace atssim::solver::sosd
