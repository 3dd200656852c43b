#pragma once
// Value, gradient and Hessian of the incremental potential in double, from
// the shared element math (kernels/common/energy_*.h): what the Newton
// reference minimises.
#include <vector>

#include <Eigen/Core>
#include <Eigen/SparseCore>

#include "solver/energy/incremental_potential.hpp"

namespace atssim::solver::energy {

struct EnergyTerms {
  double inertia = 0.0;  // 1/2 h^-2 sum m |x - x~|^2
  double stretch = 0.0;
  double bend = 0.0;
  double tet = 0.0;              // sum V Psi(F) over the tetrahedra
  double contact = 0.0;          // the colliders' contact energy
  double damping = 0.0;          // the springs' damping terms (DampingTerm)
  double surface_contact = 0.0;  // contact between simulated surfaces
  double total() const { return inertia + stretch + bend + tet + contact + damping + surface_contact; }
};

// x: 3 per particle, pinned ones included (they enter the elastic terms).
EnergyTerms energy_terms(const IncrementalPotential& p, const Eigen::VectorXd& x);
double total_energy(const IncrementalPotential& p, const Eigen::VectorXd& x);

// dE/dx, 3 per particle; the rows of pinned particles are 0 (no variables).
Eigen::VectorXd gradient(const IncrementalPotential& p, const Eigen::VectorXd& x);

// The Hessian as triplets over all 3 n rows and columns (duplicates add up),
// the rows and columns of pinned particles left out. With project_psd every
// element Hessian is projected to be positive semi-definite (stretch: its
// 3x3 block; a tet: its whole 12x12 matrix, eigenvalues clamped at 0, before
// pinned rows are dropped), so the sum with M/h^2 is positive definite.
std::vector<Eigen::Triplet<double>> hessian_triplets(const IncrementalPotential& p, const Eigen::VectorXd& x,
                                                     bool project_psd);

}  // namespace atssim::solver::energy
