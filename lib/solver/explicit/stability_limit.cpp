#include "solver/explicit/stability_limit.hpp"

#include <algorithm>
#include <array>
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

double step_spectral_radius(Integrator integrator, double w2, double g, double h) {
  // z = (x, v), z' = A z, A = [[0, 1], [-w², -g]].
  using M2 = std::array<double, 4>;  // row-major
  const auto mul = [](const M2& a, const M2& b) {
    return M2{a[0] * b[0] + a[1] * b[2], a[0] * b[1] + a[1] * b[3], a[2] * b[0] + a[3] * b[2],
              a[2] * b[1] + a[3] * b[3]};
  };
  M2 step{};
  if (integrator == Integrator::semi_euler) {
    // v+ = (1 - h g) v - h w² x; x+ = x + h v+.
    step = {1.0 - h * h * w2, h * (1.0 - h * g), -h * w2, 1.0 - h * g};
  } else {
    const M2 ha{0.0, h, -h * w2, -h * g};
    M2 term{1.0, 0.0, 0.0, 1.0};
    step = term;
    const int order = integrator == Integrator::midpoint ? 2 : 4;
    for (int k = 1; k <= order; ++k) {
      term = mul(term, ha);
      for (double& t : term) t /= k;
      for (int j = 0; j < 4; ++j) step[j] += term[j];
    }
  }
  const double tr = step[0] + step[3], det = step[0] * step[3] - step[1] * step[2];
  const double disc = 0.25 * tr * tr - det;
  if (disc < 0.0) return std::sqrt(std::max(det, 0.0));
  const double r = std::sqrt(disc);
  return std::max(std::abs(0.5 * tr + r), std::abs(0.5 * tr - r));
}

double stable_step(Integrator integrator, double largest_eigenvalue, double drag, double beta) {
  if (!(drag > 0.0) && !(beta > 0.0)) return stable_step(integrator, largest_eigenvalue);
  if (!(largest_eigenvalue > 0.0)) return std::numeric_limits<double>::infinity();
  const double w2 = largest_eigenvalue, g = drag + beta * w2;
  const double tolerance = integrator == Integrator::midpoint ? 1e-4 : 1e-12;
  const auto stable = [&](double h) { return step_spectral_radius(integrator, w2, g, h) <= 1.0 + tolerance; };
  // Every limit lies below 4/w (the undamped boundaries, 2.83/w at most; the
  // fast eigenvalue of a damped mode is at least w in size) and above 0.
  const double top = 4.0 / std::sqrt(w2);
  constexpr int kScan = 4000;
  double lo = 0.0, hi = top;
  for (int k = 1; k <= kScan; ++k) {
    const double h = top * k / kScan;
    if (!stable(h)) {
      hi = h;
      break;
    }
    lo = h;
  }
  for (int k = 0; k < 60; ++k) (stable(0.5 * (lo + hi)) ? lo : hi) = 0.5 * (lo + hi);
  return lo;
}

void require_stable_step(const SimLayout& layout, Integrator integrator, double h, int substeps) {
  double beta = 0.0;
  for (const ats_distance_c& c : layout.stretch) beta = std::max(beta, double(c.damping));
  const double limit = stable_step(integrator, largest_eigenvalue_bound(layout), double(layout.air_drag), beta);
  if (h <= limit) return;
  const double needed = std::ceil(substeps * h / limit);
  throw input_error(fmt::format(
      "solver.method explicit ({}): the substep {:.3g} s exceeds the estimated stable step {:.3g} s (Gershgorin bound "
      "on M⁻¹K, with the air drag and spring damping); use simulation.substeps ≥ {:.0f}, or --set "
      "solver.allow_unstable=true",
      kIntegratorNames[static_cast<int>(integrator)], h, limit, needed));
}

}  // namespace atssim::solver::explicit_rk
