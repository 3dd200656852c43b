#include "solver/energy/element_math.hpp"  // first: the double instance of the shared math

#include "solver/energy/potential_evaluation.hpp"
#include "solver/energy/self_contact_energy.hpp"

#include <Eigen/Eigenvalues>

namespace atssim::solver::energy {

namespace {

using f64::ats_mat3;
using f64::ats_vec3;

ats_vec3 vec_at(const Eigen::VectorXd& x, int i) { return f64::ats_v3(x[3 * i], x[3 * i + 1], x[3 * i + 2]); }

void add_at(Eigen::VectorXd& g, int i, ats_vec3 v) {
  g[3 * i] += v.x;
  g[3 * i + 1] += v.y;
  g[3 * i + 2] += v.z;
}

ats_vec3 start_a(const DampingTerm& t) { return f64::ats_v3(t.start_a[0], t.start_a[1], t.start_a[2]); }
ats_vec3 start_b(const DampingTerm& t) { return f64::ats_v3(t.start_b[0], t.start_b[1], t.start_b[2]); }

void bend_positions(const BendTerm& t, const Eigen::VectorXd& x, ats_vec3 out[4]) {
  for (int k = 0; k < 4; ++k) out[k] = vec_at(x, t.v[k]);
}

using Matrix12d = Eigen::Matrix<double, 12, 12>;

void tet_positions(const TetTerm& t, const Eigen::VectorXd& x, ats_vec3 out[4]) {
  for (int k = 0; k < 4; ++k) out[k] = vec_at(x, t.v[k]);
}

ats_mat3 dm_inv_of(const TetTerm& t) {
  const auto& m = t.dm_inv;
  return {{f64::ats_v3(m[0], m[1], m[2]), f64::ats_v3(m[3], m[4], m[5]), f64::ats_v3(m[6], m[7], m[8])}};
}

double tet_energy(const TetTerm& t, const ats_vec3 q[4]) {
  const ats_mat3 dm = dm_inv_of(t);
  return t.model == TetModel::stvk ? f64::ats_tet_stvk_energy(q, dm, t.volume, t.mu, t.lambda)
                                   : f64::ats_tet_nh_energy(q, dm, t.volume, t.mu, t.lambda);
}

ats_vec3 tet_gradient(const TetTerm& t, const ats_vec3 q[4], int a) {
  const ats_mat3 dm = dm_inv_of(t);
  return t.model == TetModel::stvk ? f64::ats_tet_stvk_gradient(q, dm, t.volume, t.mu, t.lambda, a)
                                   : f64::ats_tet_nh_gradient(q, dm, t.volume, t.mu, t.lambda, a);
}

// The 12x12 element Hessian from its 4x4 blocks; with project_psd its
// negative eigenvalues are clamped to 0. The whole element, not each 3x3
// block: a sum of PSD blocks placed off the diagonal need not be PSD.
Matrix12d tet_hessian(const TetTerm& t, const ats_vec3 q[4], bool project_psd) {
  const ats_mat3 dm = dm_inv_of(t);
  Matrix12d h;
  for (int a = 0; a < 4; ++a) {
    for (int b = 0; b < 4; ++b) {
      const ats_mat3 m = t.model == TetModel::stvk ? f64::ats_tet_stvk_hessian(q, dm, t.volume, t.mu, t.lambda, a, b)
                                                   : f64::ats_tet_nh_hessian(q, dm, t.volume, t.mu, t.lambda, a, b);
      for (int r = 0; r < 3; ++r) h.block<1, 3>(3 * a + r, 3 * b) << m.r[r].x, m.r[r].y, m.r[r].z;
    }
  }
  if (!project_psd) return h;
  const Eigen::SelfAdjointEigenSolver<Matrix12d> eig(0.5 * (h + h.transpose()));
  const auto& v = eig.eigenvectors();
  return v * eig.eigenvalues().cwiseMax(0.0).asDiagonal() * v.transpose();
}

// Appends the block (i, j) of a 3x3 matrix unless either particle is pinned.
void add_block(std::vector<Eigen::Triplet<double>>& out, const IncrementalPotential& p, int i, int j, const ats_mat3& m,
               double sign) {
  if (!p.is_free(i) || !p.is_free(j)) return;
  for (int r = 0; r < 3; ++r) {
    const double row[3] = {m.r[r].x, m.r[r].y, m.r[r].z};
    for (int c = 0; c < 3; ++c) out.emplace_back(3 * i + r, 3 * j + c, sign * row[c]);
  }
}

void add_block(std::vector<Eigen::Triplet<double>>& out, const IncrementalPotential& p, int i, int j,
               const Eigen::Matrix3d& m) {
  if (!p.is_free(i) || !p.is_free(j)) return;
  for (int r = 0; r < 3; ++r) {
    for (int c = 0; c < 3; ++c) out.emplace_back(3 * i + r, 3 * j + c, m(r, c));
  }
}

}  // namespace

EnergyTerms energy_terms(const IncrementalPotential& p, const Eigen::VectorXd& x) {
  EnergyTerms e;
  const double inv_h2 = 1.0 / (p.h * p.h);
  for (int i = 0; i < p.particle_count(); ++i) {
    if (!p.is_free(i)) continue;
    e.inertia += f64::ats_inertia_energy(vec_at(x, i), vec_at(p.predicted, i), p.mass[i], inv_h2);
    for (int c = 0; c < p.collider_count; ++c)
      e.contact += f64::ats_contact_energy(&p.colliders[c], vec_at(x, i), p.mass[i], inv_h2);
  }
  for (const StretchTerm& t : p.stretch) {
    e.stretch += f64::ats_stretch_energy(vec_at(x, t.a), vec_at(x, t.b), t.rest, t.stiffness);
  }
  for (const BendTerm& t : p.bend) {
    ats_vec3 q[4];
    bend_positions(t, x, q);
    e.bend += f64::ats_bend_element_energy(t.model, q, t.K.data(), t.scale, t.stiffness, t.rest_angle);
  }
  for (const TetTerm& t : p.tets) {
    ats_vec3 q[4];
    tet_positions(t, x, q);
    e.tet += tet_energy(t, q);
  }
  for (const DampingTerm& t : p.damping) {
    e.damping += f64::ats_spring_damping_energy(vec_at(x, t.a), vec_at(x, t.b), start_a(t), start_b(t), t.c_over_h);
  }
  e.surface_contact = surface_contact_energy(p.surface_contact, x);
  return e;
}

double total_energy(const IncrementalPotential& p, const Eigen::VectorXd& x) { return energy_terms(p, x).total(); }

Eigen::VectorXd gradient(const IncrementalPotential& p, const Eigen::VectorXd& x) {
  Eigen::VectorXd g = Eigen::VectorXd::Zero(x.size());
  const double inv_h2 = 1.0 / (p.h * p.h);
  for (int i = 0; i < p.particle_count(); ++i) {
    if (!p.is_free(i)) continue;
    add_at(g, i, f64::ats_inertia_gradient(vec_at(x, i), vec_at(p.predicted, i), p.mass[i], inv_h2));
    for (int c = 0; c < p.collider_count; ++c)
      add_at(g, i, f64::ats_contact_gradient(&p.colliders[c], vec_at(x, i), p.mass[i], inv_h2));
  }
  for (const StretchTerm& t : p.stretch) {
    const ats_vec3 ga = f64::ats_stretch_gradient(vec_at(x, t.a), vec_at(x, t.b), t.rest, t.stiffness);
    add_at(g, t.a, ga);
    add_at(g, t.b, f64::ats_scale(ga, -1.0));
  }
  for (const BendTerm& t : p.bend) {
    ats_vec3 q[4];
    bend_positions(t, x, q);
    for (int k = 0; k < 4; ++k) {
      add_at(g, t.v[k], f64::ats_bend_element_gradient(t.model, q, t.K.data(), t.scale, t.stiffness, t.rest_angle, k));
    }
  }
  for (const TetTerm& t : p.tets) {
    ats_vec3 q[4];
    tet_positions(t, x, q);
    for (int k = 0; k < 4; ++k) add_at(g, t.v[k], tet_gradient(t, q, k));
  }
  for (const DampingTerm& t : p.damping) {
    const ats_vec3 ga =
        f64::ats_spring_damping_gradient(vec_at(x, t.a), vec_at(x, t.b), start_a(t), start_b(t), t.c_over_h);
    add_at(g, t.a, ga);
    add_at(g, t.b, f64::ats_scale(ga, -1.0));
  }
  add_surface_contact_gradient(p.surface_contact, x, g);
  for (int i = 0; i < p.particle_count(); ++i) {
    if (!p.is_free(i)) g.segment<3>(3 * i).setZero();
  }
  return g;
}

std::vector<Eigen::Triplet<double>> hessian_triplets(const IncrementalPotential& p, const Eigen::VectorXd& x,
                                                     bool project_psd) {
  std::vector<Eigen::Triplet<double>> out;
  out.reserve(9 * (p.mass.size() + 4 * p.stretch.size() + 16 * (p.bend.size() + p.tets.size())));
  const double inv_h2 = 1.0 / (p.h * p.h);
  for (int i = 0; i < p.particle_count(); ++i) {
    if (!p.is_free(i)) continue;
    add_block(out, p, i, i, f64::ats_inertia_hessian(p.mass[i], inv_h2), 1.0);
    for (int c = 0; c < p.collider_count; ++c) {
      add_block(out, p, i, i, f64::ats_contact_hessian(&p.colliders[c], vec_at(x, i), p.mass[i], inv_h2), 1.0);
    }
  }
  for (const StretchTerm& t : p.stretch) {
    const ats_mat3 h = f64::ats_stretch_hessian(vec_at(x, t.a), vec_at(x, t.b), t.rest, t.stiffness, project_psd);
    add_block(out, p, t.a, t.a, h, 1.0);
    add_block(out, p, t.b, t.b, h, 1.0);
    add_block(out, p, t.a, t.b, h, -1.0);
    add_block(out, p, t.b, t.a, h, -1.0);
  }
  for (const BendTerm& t : p.bend) {
    ats_vec3 q[4];
    bend_positions(t, x, q);
    for (int i = 0; i < 4; ++i) {
      for (int j = 0; j < 4; ++j) {
        add_block(out, p, t.v[i], t.v[j],
                  f64::ats_bend_element_hessian(t.model, q, t.K.data(), t.scale, t.stiffness, i, j), 1.0);
      }
    }
  }
  for (const TetTerm& t : p.tets) {
    ats_vec3 q[4];
    tet_positions(t, x, q);
    const Matrix12d h = tet_hessian(t, q, project_psd);
    for (int i = 0; i < 4; ++i) {
      for (int j = 0; j < 4; ++j) add_block(out, p, t.v[i], t.v[j], h.block<3, 3>(3 * i, 3 * j));
    }
  }
  for (const DampingTerm& t : p.damping) {
    const ats_mat3 h = f64::ats_spring_damping_hessian(start_a(t), start_b(t), t.c_over_h);
    add_block(out, p, t.a, t.a, h, 1.0);
    add_block(out, p, t.b, t.b, h, 1.0);
    add_block(out, p, t.a, t.b, h, -1.0);
    add_block(out, p, t.b, t.a, h, -1.0);
  }
  add_surface_contact_hessian(p, x, out);
  return out;
}

}  // namespace atssim::solver::energy
