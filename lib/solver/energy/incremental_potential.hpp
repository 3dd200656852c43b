#pragma once
// The incremental potential of one substep (He et al. 2025 §3.1, Eq. 1),
//   E(x) = 1/2 h^-2 sum_i m_i |x_i - x~_i|^2 + Psi(x),
//   Psi  = sum_stretch 1/2 alpha^-1 (|x_a - x_b| - L)^2 + sum_bend 1/2 alpha^-1 |C|^2,
// whose minimiser is what XPBD with compliance alpha converges to (Macklin
// et al. 2016, Eq. 4 and §3). Built from the XPBD layout, the very float data
// the XPBD solver and kernels see, converted to double: the reference then
// solves exactly XPBD's problem, not one that differs by float rounding.
#include <array>
#include <vector>

#include <Eigen/Core>

#include "solver/xpbd/xpbd_layout.hpp"

namespace atssim::solver::energy {

struct StretchTerm {
  int a = 0, b = 0;
  double rest = 0.0;
  double stiffness = 0.0;  // 1 / compliance
};

struct BendTerm {
  std::array<int, 4> v{};
  std::array<double, 4> K{};
  double scale = 0.0;
  double stiffness = 0.0;  // 1 / compliance
};

struct IncrementalPotential {
  double h = 0.0;
  Eigen::VectorXd predicted;  // x~, 3 per particle (pinned: their fixed position)
  std::vector<double> mass;   // m_i = 1 / w_i; 0 marks a pinned particle (no variable)
  std::vector<StretchTerm> stretch;
  std::vector<BendTerm> bend;

  int particle_count() const { return static_cast<int>(mass.size()); }
  bool is_free(int i) const { return mass[i] > 0.0; }
};

// Throws atssim::Error (input) when a constraint has compliance 0: an
// infinitely stiff constraint has no finite energy, so converging needs
// finite stiffness. Also when predicted and the layout differ in size.
IncrementalPotential make_incremental_potential(const xpbd::XpbdLayout& layout,
                                                const std::vector<xpbd::Float4>& predicted, double h);

// xyz of float4 positions as one vector of 3 n doubles.
Eigen::VectorXd positions_of(const std::vector<xpbd::Float4>& x);

// E at the layout's positions (layout.x), in double; masses from layout.x[i].w.
double incremental_potential(const xpbd::XpbdLayout& layout, const std::vector<xpbd::Float4>& predicted, double h);

}  // namespace atssim::solver::energy
