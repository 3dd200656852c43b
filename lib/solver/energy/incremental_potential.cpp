#include "solver/energy/incremental_potential.hpp"

#include <fmt/format.h>

#include "solver/energy/finite_stiffness.hpp"
#include "solver/energy/potential_evaluation.hpp"
#include "util/error.hpp"

namespace atssim::solver::energy {

IncrementalPotential make_incremental_potential(const SimLayout& layout, const std::vector<Float4>& predicted, double h,
                                                const std::vector<Float4>* start) {
  if (predicted.size() != layout.x.size()) {
    throw internal_error(fmt::format("incremental potential: {} predicted positions for {} particles", predicted.size(),
                                     layout.x.size()));
  }
  require_finite_stiffness(layout);
  require_valid_tets(layout);
  IncrementalPotential p;
  p.h = inertia_dt(layout, h);  // air drag weighs the inertia as for this step (sim_layout.hpp)
  p.predicted = positions_of(predicted);
  p.mass.resize(layout.x.size());
  for (std::size_t i = 0; i < layout.x.size(); ++i) {
    const double w = layout.x[i].w;
    p.mass[i] = w > 0.0 ? 1.0 / w : 0.0;
  }
  const std::vector<Float4>& x0 = start != nullptr ? *start : layout.x;
  if (x0.size() != layout.x.size()) {
    throw internal_error(
        fmt::format("incremental potential: {} start positions for {} particles", x0.size(), layout.x.size()));
  }
  p.stretch.reserve(layout.stretch.size());
  for (std::size_t i = 0; i < layout.stretch.size(); ++i) {
    const ats_distance_c& c = layout.stretch[i];
    p.stretch.push_back({c.a, c.b, c.rest, 1.0 / static_cast<double>(c.compliance)});
    if (c.damping > 0.0f) {
      const Float4 &qa = x0[c.a], &qb = x0[c.b];
      p.damping.push_back({c.a,
                           c.b,
                           {qa.x, qa.y, qa.z},
                           {qb.x, qb.y, qb.z},
                           static_cast<double>(c.damping) / static_cast<double>(c.compliance) / h});
    }
  }
  p.bend.reserve(layout.bend.size());
  for (std::size_t i = 0; i < layout.bend.size(); ++i) {
    const ats_bend_c& c = layout.bend[i];
    BendTerm t;
    for (int k = 0; k < 4; ++k) {
      t.v[k] = c.v[k];
      t.K[k] = c.K[k];
    }
    t.scale = c.scale;
    t.stiffness = 1.0 / static_cast<double>(c.compliance);
    t.rest_angle = c.rest_angle;
    t.model = c.model;
    p.bend.push_back(t);
  }
  p.tets.reserve(layout.tets.size());
  for (const ats_tet_c& c : layout.tets) {
    TetTerm t;
    for (int k = 0; k < 4; ++k) t.v[k] = c.v[k];
    for (int k = 0; k < 9; ++k) t.dm_inv[k] = c.dm_inv[k];
    t.volume = c.volume;
    t.mu = c.mu;
    t.lambda = c.lambda;
    t.model = c.model == ATS_TET_STVK ? TetModel::stvk : TetModel::neo_hookean;
    p.tets.push_back(t);
  }
  p.colliders = layout.colliders;
  p.collider_count = layout.collider_count;
  if (layout.self_contact.enabled) {
    for (const auto& t : layout.self_contact.tris) p.surface_contact.tris.push_back({t[0], t[1], t[2]});
    p.surface_contact.edges = layout.self_contact.edges;
    p.surface_contact.k = self_contact_k(layout.self_contact, p.h);
    p.surface_contact.r = layout.self_contact.thickness;
  }
  return p;
}

Eigen::VectorXd positions_of(const std::vector<Float4>& x) {
  Eigen::VectorXd out(3 * static_cast<Eigen::Index>(x.size()));
  for (std::size_t i = 0; i < x.size(); ++i) out.segment<3>(3 * static_cast<Eigen::Index>(i)) << x[i].x, x[i].y, x[i].z;
  return out;
}

double incremental_potential(const SimLayout& layout, const std::vector<Float4>& predicted, double h,
                             const std::vector<Float4>* start) {
  return total_energy(make_incremental_potential(layout, predicted, h, start), positions_of(layout.x));
}

}  // namespace atssim::solver::energy
