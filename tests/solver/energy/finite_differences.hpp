#pragma once
// Central finite differences: the independent reference for the analytic
// gradients and Hessians of the energy terms.
#include <functional>

#include <Eigen/Core>

namespace atssim::test {

inline Eigen::VectorXd fd_gradient(const std::function<double(const Eigen::VectorXd&)>& f, const Eigen::VectorXd& x,
                                   double step = 1e-6) {
  Eigen::VectorXd g(x.size());
  for (Eigen::Index i = 0; i < x.size(); ++i) {
    Eigen::VectorXd a = x, b = x;
    a[i] += step;
    b[i] -= step;
    g[i] = (f(a) - f(b)) / (2.0 * step);
  }
  return g;
}

// Column j = d grad / d x_j.
inline Eigen::MatrixXd fd_jacobian(const std::function<Eigen::VectorXd(const Eigen::VectorXd&)>& g,
                                   const Eigen::VectorXd& x, double step = 1e-6) {
  const Eigen::Index n = x.size();
  Eigen::MatrixXd J(g(x).size(), n);
  for (Eigen::Index j = 0; j < n; ++j) {
    Eigen::VectorXd a = x, b = x;
    a[j] += step;
    b[j] -= step;
    J.col(j) = (g(a) - g(b)) / (2.0 * step);
  }
  return J;
}

}  // namespace atssim::test
