#include "solver/explicit/stability_limit.hpp"

#include <cmath>
#include <limits>
#include <vector>

#include <fmt/format.h>

#include "common/energy_dihedral.h"
#include "util/error.hpp"

namespace atssim::solver::explicit_rk {

namespace {

double norm3(ats_vec3 v) { return std::sqrt(double(v.x) * v.x + double(v.y) * v.y + double(v.z) * v.z); }

}  // namespace

double largest_eigenvalue_bound(const SimLayout& layout) {
  const std::size_t n = layout.x.size();
  std::vector<double> row(n, 0.0);  // Σ_j ‖K_ij‖ per particle
  for (const ats_distance_c& c : layout.stretch) {
    const double k = 1.0 / double(c.compliance);
    row[c.a] += 2.0 * k;  // ‖K_aa‖ + ‖K_ab‖
    row[c.b] += 2.0 * k;
  }
  for (const ats_bend_c& c : layout.bend) {
    const double k = 1.0 / double(c.compliance);
    double g[4];
    if (c.model == ATS_BEND_DIHEDRAL) {
      ats_vec3 q[4];
      for (int j = 0; j < 4; ++j) q[j] = ats_v3(layout.x[c.v[j]].x, layout.x[c.v[j]].y, layout.x[c.v[j]].z);
      for (int j = 0; j < 4; ++j) g[j] = norm3(ats_dihedral_angle_gradient(q, j)) * std::sqrt(2.0 * k * c.scale);
    } else {
      for (int j = 0; j < 4; ++j) g[j] = std::abs(double(c.K[j])) * std::sqrt(k * c.scale);
    }
    const double sum = g[0] + g[1] + g[2] + g[3];
    for (int j = 0; j < 4; ++j) row[c.v[j]] += g[j] * sum;
  }
  for (const ats_tet_c& t : layout.tets) {
    // F = Σ_k (x_k − x_0) ⊗ row k−1 of Dm⁻¹: g_k is that row, g_0 = −(g_1 + g_2 + g_3).
    double g[4];
    double s[3] = {0.0, 0.0, 0.0};
    for (int k = 1; k < 4; ++k) {
      double len2 = 0.0;
      for (int c = 0; c < 3; ++c) {
        const double e = t.dm_inv[3 * (k - 1) + c];
        len2 += e * e;
        s[c] += e;
      }
      g[k] = std::sqrt(len2);
    }
    g[0] = std::sqrt(s[0] * s[0] + s[1] * s[1] + s[2] * s[2]);
    const double c = double(t.volume) * (double(t.lambda) + 2.0 * double(t.mu));
    const double sum = g[0] + g[1] + g[2] + g[3];
    for (int j = 0; j < 4; ++j) row[t.v[j]] += c * g[j] * sum;
  }
  double worst = 0.0;
  for (std::size_t i = 0; i < n; ++i) {
    if (layout.x[i].w > 0.0f) worst = std::max(worst, double(layout.x[i].w) * row[i]);
  }
  return worst;
}

double stable_step(Integrator integrator, double largest_eigenvalue) {
  if (!(largest_eigenvalue > 0.0)) return std::numeric_limits<double>::infinity();
  const double omega = std::sqrt(largest_eigenvalue);
  switch (integrator) {
    case Integrator::semi_euler:
      return 2.0 / omega;
    case Integrator::midpoint:
      return std::pow(8e-4, 0.25) / omega;
    case Integrator::rk4:
      break;
  }
  return 2.0 * std::sqrt(2.0) / omega;
}

void require_stable_step(const SimLayout& layout, Integrator integrator, double h, int substeps) {
  const double limit = stable_step(integrator, largest_eigenvalue_bound(layout));
  if (h <= limit) return;
  const double needed = std::ceil(substeps * h / limit);
  throw input_error(fmt::format(
      "solver.method explicit ({}): the substep {:.3g} s exceeds the estimated stable step {:.3g} s (Gershgorin bound "
      "on M⁻¹K); use simulation.substeps ≥ {:.0f}, or --set solver.allow_unstable=true",
      kIntegratorNames[static_cast<int>(integrator)], h, limit, needed));
}

}  // namespace atssim::solver::explicit_rk
