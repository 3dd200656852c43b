#include "solver/newton/newton_reference.hpp"

#include <cmath>
#include <limits>

#include <Eigen/SparseCholesky>

#include "solver/energy/potential_evaluation.hpp"
#include "solver/newton/free_dofs.hpp"

namespace atssim::solver::newton {

namespace {

// Near the minimum the decrease of E drops below the rounding of its sum and
// Armijo can no longer tell; there a step that still lowers |grad E| is taken.
constexpr double kEnergyRounding = 1e-13;

struct Point {
  Eigen::VectorXd x;
  double energy = 0.0;
  Eigen::VectorXd gradient;  // free coordinates
};

Point evaluate(const energy::IncrementalPotential& p, const FreeDofs& dofs, Eigen::VectorXd x) {
  Point out;
  out.energy = energy::total_energy(p, x);
  out.gradient = restrict_to_free(dofs, energy::gradient(p, x));
  out.x = std::move(x);
  return out;
}

// Backtracking from the full Newton step; false when no step length works.
bool line_search(const energy::IncrementalPotential& p, const FreeDofs& dofs, const NewtonSettings& s, const Point& at,
                 const Eigen::VectorXd& direction, Point& next) {
  const double slope = at.gradient.dot(direction);
  if (!(slope < 0.0)) return false;
  double step = 1.0;
  for (int b = 0; b <= s.max_backtracks; ++b, step *= 0.5) {
    Eigen::VectorXd x = at.x;
    add_free(dofs, step * direction, x);
    const double e = energy::total_energy(p, x);
    if (!std::isfinite(e)) continue;
    if (e <= at.energy + s.armijo * step * slope) {
      next = evaluate(p, dofs, std::move(x));
      return true;
    }
    if (e - at.energy <= kEnergyRounding * std::abs(at.energy)) {
      Point trial = evaluate(p, dofs, std::move(x));
      if (trial.gradient.norm() < at.gradient.norm()) {
        next = std::move(trial);
        return true;
      }
    }
  }
  return false;
}

}  // namespace

std::string_view to_string(NewtonStatus status) {
  switch (status) {
    case NewtonStatus::converged:
      return "converged";
    case NewtonStatus::iteration_limit:
      return "iteration limit reached";
    case NewtonStatus::line_search_failed:
      return "line search failed";
    case NewtonStatus::factorization_failed:
      return "Hessian factorization failed";
  }
  return "unknown";
}

NewtonResult newton_reference(const energy::IncrementalPotential& problem, const Eigen::VectorXd& x0,
                              const NewtonSettings& settings) {
  const FreeDofs dofs = free_dofs(problem);
  Point at = evaluate(problem, dofs, x0);
  const double initial_norm = at.gradient.norm();
  NewtonResult result;
  auto finish = [&](NewtonStatus status) {
    result.status = status;
    result.energy = at.energy;
    result.gradient_norm = at.gradient.norm();
    result.relative_gradient = initial_norm > 0.0 ? result.gradient_norm / initial_norm : 0.0;
    result.x = std::move(at.x);
    return result;
  };
  auto converged = [&] {
    const double norm = at.gradient.norm();
    return norm <= settings.absolute_tolerance || norm < settings.relative_tolerance * initial_norm;
  };
  if (converged()) return finish(NewtonStatus::converged);

  Eigen::SimplicialLDLT<Eigen::SparseMatrix<double>> solver;
  for (int it = 0; it < settings.max_iterations; ++it) {
    const Eigen::SparseMatrix<double> H =
        free_matrix(dofs, energy::hessian_triplets(problem, at.x, settings.project_psd));
    // Every element emits all its entries, so the pattern never changes.
    if (it == 0) solver.analyzePattern(H);
    solver.factorize(H);
    if (solver.info() != Eigen::Success) return finish(NewtonStatus::factorization_failed);
    const Eigen::VectorXd direction = solver.solve(-at.gradient);
    Point next;
    if (!line_search(problem, dofs, settings, at, direction, next)) return finish(NewtonStatus::line_search_failed);
    at = std::move(next);
    result.iterations = it + 1;
    if (converged()) return finish(NewtonStatus::converged);
  }
  return finish(NewtonStatus::iteration_limit);
}

NewtonResult newton_reference(const xpbd::XpbdLayout& layout, const std::vector<xpbd::Float4>& predicted, double h,
                              const NewtonSettings& settings) {
  const energy::IncrementalPotential problem = energy::make_incremental_potential(layout, predicted, h);
  return newton_reference(problem, problem.predicted, settings);
}

}  // namespace atssim::solver::newton
