#pragma once
// The contact energy between simulated surfaces in double, for the
// incremental potential and the Newton reference: the pairs are found by
// brute force over the surface at x (box test, then the distance), so this
// is an independent check of the device's BVH detection too. Quadratic in
// the surface size: meant for the scenes `converge` and the tests run.
#include <array>
#include <vector>

#include <Eigen/Core>
#include <Eigen/SparseCore>

#include "solver/energy/incremental_potential.hpp"

namespace atssim::solver::energy {

// A pair closer than the term's r: vertex-triangle (v = point, a, b, c) or
// edge-edge (v = p0, p1, q0, q1); incident pairs and sheet neighbours
// (solver/energy/sheet_neighbours) excluded, each pair once.
struct SurfacePair {
  bool edge_edge = false;
  std::array<int, 4> v{};
};

std::vector<SurfacePair> surface_pairs(const SurfaceContactTerm& term, const Eigen::VectorXd& x);

double surface_contact_energy(const SurfaceContactTerm& term, const Eigen::VectorXd& x);
void add_surface_contact_gradient(const SurfaceContactTerm& term, const Eigen::VectorXd& x, Eigen::VectorXd& g);
// Gauss-Newton blocks k w_i w_j n n^T of every pair (positive semi-definite),
// rows and columns of pinned particles left out.
void add_surface_contact_hessian(const IncrementalPotential& p, const Eigen::VectorXd& x,
                                 std::vector<Eigen::Triplet<double>>& out);

}  // namespace atssim::solver::energy
