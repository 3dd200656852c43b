#pragma once
// The incremental potential of one substep (He et al. 2025 §3.1, Eq. 1),
//   E(x) = 1/2 h^-2 sum_i m_i |x_i - x~_i|^2 + Psi(x),
//   Psi  = sum_stretch 1/2 alpha^-1 (|x_a - x_b| - L)^2 + sum_bend 1/2 alpha^-1 |C|^2
//          (isometric; dihedral stencils: scale alpha^-1 (theta - theta_0)^2)
//        + sum_tet V Psi_tet(F) + sum_i sum_colliders E_c(x_i)
//        + sum_damped springs 1/2 (c/h) (n0 . (dx_a - dx_b))^2 (DampingTerm),
// whose constraint part XPBD with compliance alpha converges to (Macklin et
// al. 2016, Eq. 4 and §3); the tets are the hyperelastic energies of
// kernels/common/energy_tet_*.h (stable neo-Hookean or StVK). Built from the
// XPBD layout, the very float data the solvers and kernels see, converted to
// double: the reference then solves exactly their problem, not one that
// differs by float rounding. E_c is the contact energy of a particle and an
// analytic collider (kernels/common/collider_distance.h), the one the
// vertex-block methods minimise.
#include <array>
#include <vector>

#include <Eigen/Core>

#include "solver/layout/sim_layout.hpp"

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
  double stiffness = 0.0;          // 1 / compliance
  double rest_angle = 0.0;         // dihedral model: theta_0 (radians)
  int model = ATS_BEND_ISOMETRIC;  // common/element_types.h
};

// Material damping of a spring, taken at the end-of-substep velocity: the
// quadratic 1/2 (c/h) (n0 . ((x_a - x0_a) - (x_b - x0_b)))^2 with n0 the
// direction at the substep's start x0 (kernels/common/energy_spring_damping.h).
struct DampingTerm {
  int a = 0, b = 0;
  std::array<double, 3> start_a{}, start_b{};  // x0 of a and b
  double c_over_h = 0.0;                       // beta k / h, N/m
};

enum class TetModel { neo_hookean, stvk };

// A linear tetrahedron: E = V Psi(F), F = Ds Dm^-1 (tet_kinematics.h).
struct TetTerm {
  std::array<int, 4> v{};
  std::array<double, 9> dm_inv{};  // Dm^-1, row-major
  double volume = 0.0;             // rest volume V
  double mu = 0.0, lambda = 0.0;   // Lame parameters
  TetModel model = TetModel::neo_hookean;
};

// Contact between simulated surfaces (common/self_contact.h): every
// vertex-triangle and edge-edge pair closer than r, incident ones and sheet
// neighbours excluded, adds 1/2 k (r - d)^2
// (solver/energy/self_contact_energy.hpp).
struct SurfaceContactTerm {
  std::vector<std::array<int, 3>> tris;  // empty: no such contact
  std::vector<std::array<int, 2>> edges;
  double k = 0.0;  // stiffness · m / h² for this potential's h
  double r = 0.0;  // thickness
};

struct IncrementalPotential {
  double h = 0.0;
  Eigen::VectorXd predicted;  // x~, 3 per particle (pinned: their fixed position)
  std::vector<double> mass;   // m_i = 1 / w_i; 0 marks a pinned particle (no variable)
  std::vector<StretchTerm> stretch;
  std::vector<BendTerm> bend;
  std::vector<TetTerm> tets;
  std::vector<DampingTerm> damping;       // springs with damping > 0 only
  std::vector<ats_collider_c> colliders;  // contact energy of every free particle with each of the first
  int collider_count = 0;                 // `collider_count` (mesh data follows them)
  SurfaceContactTerm surface_contact;

  int particle_count() const { return static_cast<int>(mass.size()); }
  bool is_free(int i) const { return mass[i] > 0.0; }
};

// Throws atssim::Error (input) when a constraint has compliance 0: an
// infinitely stiff constraint has no finite energy, so converging needs
// finite stiffness. Also when a tet has mu <= 0, lambda < 0 or an unknown
// model, and when predicted and the layout differ in size.
// `start` = the substep's start positions x_t, which the springs' damping
// terms need; nullptr = layout.x (the state the substep starts from).
IncrementalPotential make_incremental_potential(const SimLayout& layout, const std::vector<Float4>& predicted, double h,
                                                const std::vector<Float4>* start = nullptr);

// xyz of float4 positions as one vector of 3 n doubles.
Eigen::VectorXd positions_of(const std::vector<Float4>& x);

// E at the layout's positions (layout.x), in double; masses from layout.x[i].w.
double incremental_potential(const SimLayout& layout, const std::vector<Float4>& predicted, double h,
                             const std::vector<Float4>* start = nullptr);

}  // namespace atssim::solver::energy
