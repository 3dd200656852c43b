#pragma once
// Shared checks for the element energies of the shared math headers (in
// double, via solver/energy/element_math.hpp): an element is its vertex
// count and three functions of the positions — energy, gradient block a,
// Hessian block (a, b) — seen here as functions of one coordinate vector,
// so they can be compared with central finite differences.
#include <functional>
#include <random>

#include <Eigen/Core>
#include <Eigen/Geometry>

#include "solver/energy/element_math.hpp"

namespace atssim::test {

namespace f64 = atssim::solver::energy::f64;

struct ElementFunctions {
  int vertices = 4;
  std::function<double(const f64::ats_vec3*)> energy;
  std::function<f64::ats_vec3(const f64::ats_vec3*, int)> gradient;
  std::function<f64::ats_mat3(const f64::ats_vec3*, int, int)> hessian;

  static void unpack(const Eigen::VectorXd& q, f64::ats_vec3* x, int n) {
    for (int i = 0; i < n; ++i) x[i] = f64::ats_v3(q[3 * i], q[3 * i + 1], q[3 * i + 2]);
  }
  double energy_at(const Eigen::VectorXd& q) const {
    f64::ats_vec3 x[4];
    unpack(q, x, vertices);
    return energy(x);
  }
  Eigen::VectorXd gradient_at(const Eigen::VectorXd& q) const {
    f64::ats_vec3 x[4];
    unpack(q, x, vertices);
    Eigen::VectorXd g(3 * vertices);
    for (int a = 0; a < vertices; ++a) {
      const f64::ats_vec3 v = gradient(x, a);
      g.segment<3>(3 * a) << v.x, v.y, v.z;
    }
    return g;
  }
  Eigen::MatrixXd hessian_at(const Eigen::VectorXd& q) const {
    f64::ats_vec3 x[4];
    unpack(q, x, vertices);
    Eigen::MatrixXd h(3 * vertices, 3 * vertices);
    for (int a = 0; a < vertices; ++a) {
      for (int b = 0; b < vertices; ++b) h.block<3, 3>(3 * a, 3 * b) = to_eigen(hessian(x, a, b));
    }
    return h;
  }
  static Eigen::Matrix3d to_eigen(const f64::ats_mat3& m) {
    Eigen::Matrix3d out;
    out << m.r[0].x, m.r[0].y, m.r[0].z, m.r[1].x, m.r[1].y, m.r[1].z, m.r[2].x, m.r[2].y, m.r[2].z;
    return out;
  }
};

inline f64::ats_mat3 to_ats(const Eigen::Matrix3d& m) {
  f64::ats_mat3 out;
  for (int i = 0; i < 3; ++i) out.r[i] = f64::ats_v3(m(i, 0), m(i, 1), m(i, 2));
  return out;
}

inline Eigen::VectorXd pack(const std::vector<Eigen::Vector3d>& x) {
  Eigen::VectorXd q(3 * static_cast<Eigen::Index>(x.size()));
  for (std::size_t i = 0; i < x.size(); ++i) q.segment<3>(3 * static_cast<Eigen::Index>(i)) = x[i];
  return q;
}

inline std::vector<f64::ats_vec3> to_ats(const std::vector<Eigen::Vector3d>& x) {
  std::vector<f64::ats_vec3> out;
  for (const auto& p : x) out.push_back(f64::ats_v3(p.x(), p.y(), p.z()));
  return out;
}

inline Eigen::Matrix3d random_rotation(std::mt19937& rng) {
  std::normal_distribution<double> n;
  Eigen::Quaterniond q(n(rng), n(rng), n(rng), n(rng));
  return q.normalized().toRotationMatrix();
}

// A rest element: a regular-ish simplex with random jitter, scaled to ~size.
inline std::vector<Eigen::Vector3d> random_rest_tet(std::mt19937& rng, double size = 1.0) {
  std::uniform_real_distribution<double> u(-0.25, 0.25);
  std::vector<Eigen::Vector3d> x = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0, 0, 1}};
  for (auto& p : x) p = size * (p + Eigen::Vector3d(u(rng), u(rng), u(rng)));
  if ((x[1] - x[0]).cross(x[2] - x[0]).dot(x[3] - x[0]) < 0) std::swap(x[2], x[3]);
  return x;
}

// Deformed: a random linear map near the identity, a rotation, a translation and per-vertex noise.
inline std::vector<Eigen::Vector3d> random_deformation(std::mt19937& rng, const std::vector<Eigen::Vector3d>& rest,
                                                       double strain = 0.3) {
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  Eigen::Matrix3d a = Eigen::Matrix3d::Identity();
  for (int i = 0; i < 9; ++i) a(i / 3, i % 3) += strain * u(rng);
  const Eigen::Matrix3d r = random_rotation(rng);
  const Eigen::Vector3d t(u(rng), u(rng), u(rng));
  std::vector<Eigen::Vector3d> x;
  for (const auto& p : rest) x.push_back(r * a * p + t + 0.05 * strain * Eigen::Vector3d(u(rng), u(rng), u(rng)));
  return x;
}

}  // namespace atssim::test
