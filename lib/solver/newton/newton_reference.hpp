#pragma once
// A converged reference for one substep: Newton's method on the incremental
// potential E (He et al. 2025 §3.1, Eq. 1), the problem XPBD with compliance
// solves (Macklin et al. 2016), plus the elastic energy of tetrahedra.
// Sparse Hessian from the per-element matrices (3x3 blocks; 12x12 for a
// tet), each projected PSD, plus M/h^2; pinned particles eliminated;
// Eigen::SimplicialLDLT; backtracking (Armijo) line search. Accuracy of a
// solver run is then the relative energy error (E_k - E*) / (E_0 - E*).
//
// Input is the XPBD layout (energy::IncrementalPotential), not the double
// Model: it is the float data XPBD itself runs on, so E* is the minimum of
// exactly the problem XPBD iterates on.
#include <string_view>
#include <vector>

#include <Eigen/Core>

#include "solver/energy/incremental_potential.hpp"
#include "solver/layout/sim_layout.hpp"

namespace atssim::solver::newton {

enum class NewtonStatus {
  converged,             // relative (or absolute) gradient norm below tolerance
  iteration_limit,       // max_iterations steps taken without converging
  line_search_failed,    // no step length decreased E (nor, within rounding, |grad E|)
  factorization_failed,  // the projected Hessian was not positive definite
  stalled,               // steps in a row neither halved |grad E| nor lowered E beyond rounding
};

std::string_view to_string(NewtonStatus status);

struct NewtonSettings {
  int max_iterations = 100;
  double relative_tolerance = 1e-8;   // stop when |grad E| / |grad E(x0)| < this
  double absolute_tolerance = 1e-13;  // or when |grad E| < this (x0 is already the minimum)
  bool project_psd = true;            // per-element PSD projection of the Hessian
  double armijo = 1e-4;               // sufficient decrease: E(x + a d) <= E + armijo a grad.d
  int max_backtracks = 50;            // step halvings before giving up
  // The ground plane as a bound y >= ground_y on free particles (projected
  // Newton with an active set), as every solver's collision task enforces.
  bool has_ground = false;
  double ground_y = 0.0;
};

struct NewtonResult {
  Eigen::VectorXd x;               // x*, 3 per particle; pinned particles as in x0
  double energy = 0.0;             // E(x*)
  int iterations = 0;              // Newton steps taken
  double gradient_norm = 0.0;      // |grad E(x*)| over the free coordinates (those the ground does not hold)
  double relative_gradient = 0.0;  // gradient_norm / |grad E(x0)| (0 when x0 is the minimum)
  NewtonStatus status = NewtonStatus::iteration_limit;
};

// Minimises E from x0 (3 per particle). Pinned particles keep their x0.
NewtonResult newton_reference(const energy::IncrementalPotential& problem, const Eigen::VectorXd& x0,
                              const NewtonSettings& settings = {});

// The usual call: the substep of `layout` with predicted positions x~ and
// step h, started at x0 = x~ (projected onto the ground; the layout's ground
// plane bounds the minimisation). Throws atssim::Error (input) if a constraint
// has compliance 0 (no finite energy) or a tet has mu <= 0 or lambda < 0.
NewtonResult newton_reference(const SimLayout& layout, const std::vector<Float4>& predicted, double h,
                              const NewtonSettings& settings = {});

}  // namespace atssim::solver::newton
