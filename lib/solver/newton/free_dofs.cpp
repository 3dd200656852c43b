#include "solver/newton/free_dofs.hpp"

namespace atssim::solver::newton {

FreeDofs free_dofs(const energy::IncrementalPotential& p, const std::vector<char>& fixed) {
  FreeDofs d;
  d.slot.assign(3 * p.mass.size(), -1);
  for (int i = 0; i < p.particle_count(); ++i) {
    if (!p.is_free(i)) continue;
    for (int c = 3 * i; c < 3 * i + 3; ++c) {
      if (fixed.empty() || !fixed[c]) d.slot[c] = d.free_count++;
    }
  }
  return d;
}

Eigen::VectorXd restrict_to_free(const FreeDofs& dofs, const Eigen::VectorXd& full) {
  Eigen::VectorXd out(dofs.size());
  for (std::size_t c = 0; c < dofs.slot.size(); ++c) {
    if (dofs.slot[c] >= 0) out[dofs.slot[c]] = full[static_cast<Eigen::Index>(c)];
  }
  return out;
}

void add_free(const FreeDofs& dofs, const Eigen::VectorXd& free, Eigen::VectorXd& full) {
  for (std::size_t c = 0; c < dofs.slot.size(); ++c) {
    if (dofs.slot[c] >= 0) full[static_cast<Eigen::Index>(c)] += free[dofs.slot[c]];
  }
}

Eigen::SparseMatrix<double> free_matrix(const FreeDofs& dofs, const std::vector<Eigen::Triplet<double>>& full) {
  std::vector<Eigen::Triplet<double>> mapped;
  mapped.reserve(full.size());
  for (const auto& t : full) {
    const int r = dofs.slot[t.row()];
    const int c = dofs.slot[t.col()];
    if (r < 0 || c < 0) continue;
    mapped.emplace_back(r, c, t.value());
  }
  Eigen::SparseMatrix<double> m(dofs.size(), dofs.size());
  m.setFromTriplets(mapped.begin(), mapped.end());
  return m;
}

}  // namespace atssim::solver::newton
