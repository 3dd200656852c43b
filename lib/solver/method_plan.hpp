#pragma once
// One entry point from a method name to its substep plan, so the pipeline
// and the tools need not know the methods one by one.
#include <span>
#include <string>
#include <string_view>

#include "plan/substep_plan.hpp"
#include "solver/layout/sim_layout.hpp"

namespace atssim::solver {

// The methods this build knows, for messages and validation.
std::span<const std::string_view> method_names();

struct MethodOptions {
  double chebyshev_rho = 0.9;  // JPGD: spectral radius estimate for the Chebyshev weights (0 = off)
  double jacobi_step = 0.5;    // JPGD: step length on the block-Jacobi direction
  double stencil_step = 0.7;   // SOSD: step length on the combined stencil displacements
  double momentum = 0.0;       // JPGD: heavy-ball momentum; > 0 replaces Chebyshev
};

// Throws atssim::Error (input) for an unknown method, or a scene the method
// cannot solve (VBD, SOSD and JPGD need finite stiffness).
plan::SubstepPlan make_method_plan(const std::string& method, const SimLayout& layout, double substep_dt,
                                   int iterations, const MethodOptions& options = {});

// Whether the method's iterations are Gauss-Seidel (async applies) or Jacobi
// sweeps with one synchronisation each (JPGD, SOSD).
bool is_gauss_seidel(const std::string& method);

}  // namespace atssim::solver
