#pragma once
// Pinned particles are no variables of the incremental potential: Newton
// works on the 3 coordinates of each free particle only. FreeDofs maps
// between the full 3 n vectors and the free ones.
#include <vector>

#include <Eigen/Core>
#include <Eigen/SparseCore>

#include "solver/energy/incremental_potential.hpp"

namespace atssim::solver::newton {

struct FreeDofs {
  std::vector<int> slot;  // per particle: its index among free particles, -1 if pinned
  int free_count = 0;

  int size() const { return 3 * free_count; }
};

FreeDofs free_dofs(const energy::IncrementalPotential& p);

// The free rows of a full vector (3 per particle).
Eigen::VectorXd restrict_to_free(const FreeDofs& dofs, const Eigen::VectorXd& full);
// full += the free vector scattered back (pinned rows untouched).
void add_free(const FreeDofs& dofs, const Eigen::VectorXd& free, Eigen::VectorXd& full);
// The free-by-free matrix of full-index triplets (those touching a pinned
// particle are skipped; duplicates add up).
Eigen::SparseMatrix<double> free_matrix(const FreeDofs& dofs, const std::vector<Eigen::Triplet<double>>& full);

}  // namespace atssim::solver::newton
