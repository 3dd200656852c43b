#pragma once
// Block-Jacobi preconditioned gradient descent with Chebyshev acceleration
// (Wang & Yang 2016) as a substep plan: predict, then one task per
// iteration that moves every vertex at once (cut-able between devices with
// one synchronisation per iteration), then the velocity update.
#include <string_view>

#include "plan/substep_plan.hpp"
#include "solver/layout/sim_layout.hpp"
#include "solver/vertex/vertex_layout.hpp"
#include "solver/vertex/vertex_plan.hpp"

namespace atssim::solver::jpgd {

// The embedded program its plans run: kernels/jpgd/jpgd.cl.
inline constexpr std::string_view kProgram = "jpgd";

struct JpgdSettings {
  double substep_dt = 1.0 / 960.0;
  int iterations = 8;
  // Estimated spectral radius of the Jacobi iteration for the Chebyshev
  // weights (Wang 2015): 0 turns the acceleration off; too high diverges.
  double chebyshev_rho = 0.9;
  // Step length on the block-Jacobi direction (Wang & Yang 2016 use a fixed
  // step): 1 overshoots on stiff cloth, 0.5 descends.
  double step = 0.5;
  // Heavy-ball momentum (Polyak): x^{k+1} = x^k + step d + beta (x^k - x^{k-1}).
  // beta > 0 replaces the Chebyshev weights; 0 keeps them.
  double momentum = 0.0;
  vertex::JacobiOrdering ordering = vertex::JacobiOrdering::vertices;
};

// Chebyshev weights omega_1 .. omega_n: 1, 2/(2 - rho^2), 4/(4 - rho^2 omega_{k-1}).
std::vector<double> chebyshev_weights(int iterations, double rho);

plan::SubstepPlan make_jpgd_plan(const SimLayout& layout, const JpgdSettings& settings,
                                 vertex::VertexBuffers* ids = nullptr);

}  // namespace atssim::solver::jpgd
