#include "solver/newton/free_dofs.hpp"

namespace atssim::solver::newton {

FreeDofs free_dofs(const energy::IncrementalPotential& p) {
  FreeDofs d;
  d.slot.assign(p.mass.size(), -1);
  for (int i = 0; i < p.particle_count(); ++i) {
    if (p.is_free(i)) d.slot[i] = d.free_count++;
  }
  return d;
}

Eigen::VectorXd restrict_to_free(const FreeDofs& dofs, const Eigen::VectorXd& full) {
  Eigen::VectorXd out(dofs.size());
  for (std::size_t i = 0; i < dofs.slot.size(); ++i) {
    if (dofs.slot[i] >= 0) out.segment<3>(3 * dofs.slot[i]) = full.segment<3>(3 * static_cast<Eigen::Index>(i));
  }
  return out;
}

void add_free(const FreeDofs& dofs, const Eigen::VectorXd& free, Eigen::VectorXd& full) {
  for (std::size_t i = 0; i < dofs.slot.size(); ++i) {
    if (dofs.slot[i] >= 0) full.segment<3>(3 * static_cast<Eigen::Index>(i)) += free.segment<3>(3 * dofs.slot[i]);
  }
}

Eigen::SparseMatrix<double> free_matrix(const FreeDofs& dofs, const std::vector<Eigen::Triplet<double>>& full) {
  std::vector<Eigen::Triplet<double>> mapped;
  mapped.reserve(full.size());
  for (const auto& t : full) {
    const int r = dofs.slot[t.row() / 3];
    const int c = dofs.slot[t.col() / 3];
    if (r < 0 || c < 0) continue;
    mapped.emplace_back(3 * r + t.row() % 3, 3 * c + t.col() % 3, t.value());
  }
  Eigen::SparseMatrix<double> m(dofs.size(), dofs.size());
  m.setFromTriplets(mapped.begin(), mapped.end());
  return m;
}

}  // namespace atssim::solver::newton
