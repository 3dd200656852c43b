#pragma once
// Pinned particles are no variables of the incremental potential, and with a
// ground plane a coordinate held at the ground is none for the step either:
// Newton works on the free coordinates only. FreeDofs maps between the full
// 3 n vectors and the free ones.
#include <vector>

#include <Eigen/Core>
#include <Eigen/SparseCore>

#include "solver/energy/incremental_potential.hpp"

namespace atssim::solver::newton {

struct FreeDofs {
  std::vector<int> slot;  // per coordinate (3 per particle): its index among free ones, -1 if fixed
  int free_count = 0;     // free coordinates

  int size() const { return free_count; }
};

// Every coordinate of every free particle, except those with fixed[c] set
// (fixed: empty, or 3 per particle).
FreeDofs free_dofs(const energy::IncrementalPotential& p, const std::vector<char>& fixed = {});

// The free rows of a full vector (3 per particle).
Eigen::VectorXd restrict_to_free(const FreeDofs& dofs, const Eigen::VectorXd& full);
// full += the free vector scattered back (fixed rows untouched).
void add_free(const FreeDofs& dofs, const Eigen::VectorXd& free, Eigen::VectorXd& full);
// The free-by-free matrix of full-index triplets (those touching a fixed
// coordinate are skipped; duplicates add up).
Eigen::SparseMatrix<double> free_matrix(const FreeDofs& dofs, const std::vector<Eigen::Triplet<double>>& full);

}  // namespace atssim::solver::newton
