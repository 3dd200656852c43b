#pragma once
// A synthetic, reproducible state for broad-phase measurements: a 1 m square
// cloth grid of n x n vertices folded back over itself (a crease of radius
// 0.45 edges), bent by a smooth height field that both layers share and
// rippled by one that differs between them, so that the two layers come
// within the query radius over part of their overlap. Contact thickness a
// fifth of the edge and query radius three thicknesses, as
// scripts/bench_self_contact.py and model/contact_surface use.
#include <cmath>
#include <numbers>

#include "model/model.hpp"

namespace atssim::bench {

inline model::Model crumpled_sheet(int n) {
  const double edge = 1.0 / (n - 1), pi = std::numbers::pi;
  const double fold = 0.55, radius = 0.45 * edge;
  model::Model m;
  auto& p = m.particles;
  for (int i = 0; i < n; ++i) {
    for (int j = 0; j < n; ++j) {
      const double s = i * edge, v = j * edge;
      double x = s, y = 0.0;
      if (s > fold + pi * radius) {
        x = fold - (s - fold - pi * radius);
        y = 2.0 * radius;
      } else if (s > fold) {
        const double angle = (s - fold) / radius;
        x = fold + radius * std::sin(angle);
        y = radius * (1.0 - std::cos(angle));
      }
      y += 0.04 * std::sin(2.0 * pi * x / 0.3) * std::cos(2.0 * pi * v / 0.23);               // shared: keeps the gap
      y += 0.3 * edge * std::sin(2.0 * pi * s / 0.07 + 1.3) * std::sin(2.0 * pi * v / 0.11);  // differs per layer
      p.position.emplace_back(x, y, v);
      p.velocity.emplace_back(0.0, 0.0, 0.0);
      p.mass.push_back(1.0);
      p.inv_mass.push_back(1.0);
    }
  }
  model::ContactSurface surface;
  for (int i = 0; i + 1 < n; ++i) {
    for (int j = 0; j + 1 < n; ++j) {
      const int a = i * n + j, b = (i + 1) * n + j, c = (i + 1) * n + j + 1, d = i * n + j + 1;
      surface.triangles.push_back({a, b, c});
      surface.triangles.push_back({a, c, d});
    }
  }
  surface.thickness = 0.2 * edge;
  surface.query_radius = 3.0 * surface.thickness;
  surface.stiffness = 1.0;
  m.contact_surface = surface;
  return m;
}

}  // namespace atssim::bench
