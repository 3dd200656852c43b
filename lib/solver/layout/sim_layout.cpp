#include "solver/layout/sim_layout.hpp"

#include <cmath>

#include "solver/contact/collider_buffer.hpp"
#include "util/error.hpp"

namespace atssim::solver {

namespace {

template <int Arity, typename Element>
graph::ColorBlocks color(const std::vector<Element>& elements, const std::vector<char>& movable) {
  std::vector<int> flat;
  flat.reserve(elements.size() * Arity);
  for (const auto& e : elements) flat.insert(flat.end(), e.begin(), e.end());
  return graph::color_elements(flat, Arity, movable);
}

}  // namespace

std::vector<ats_collider_c> collider_records(const std::vector<model::Collider>& colliders) {
  return collider_buffer(colliders).records;
}

SimLayout make_sim_layout(const model::Model& model) {
  const auto& p = model.particles;
  SimLayout out;
  out.x.resize(p.size());
  out.v.resize(p.size());
  std::vector<char> movable(p.size());
  for (std::size_t i = 0; i < p.size(); ++i) {
    out.x[i] = {float(p.position[i].x()), float(p.position[i].y()), float(p.position[i].z()), float(p.inv_mass[i])};
    out.v[i] = {float(p.velocity[i].x()), float(p.velocity[i].y()), float(p.velocity[i].z()), 0.0f};
    movable[i] = p.inv_mass[i] > 0.0;
  }
  out.gravity = {float(model.gravity.x()), float(model.gravity.y()), float(model.gravity.z()), 0.0f};
  out.has_ground = model.ground.has_value();
  out.ground_y = out.has_ground ? float(*model.ground) : 0.0f;
  out.air_drag = float(model.air_drag);
  ColliderBuffer colliders = collider_buffer(model.colliders);
  out.colliders = std::move(colliders.records);
  out.collider_count = colliders.count;
  out.self_contact = make_self_contact_layout(model);
  out.friction.assign(model.particles.size(), {-1.0f, -1.0f});
  for (const model::ObjectRange& o : model.objects) {
    for (int k = 0; k < o.vertex_count; ++k)
      out.friction[o.vertex_offset + k] = {float(o.friction[0]), float(o.friction[1])};
  }

  if (model.stretch.size() > 0) {
    const graph::ColorBlocks blocks = color<2>(model.stretch.edges, movable);
    out.stretch_blocks = blocks.offsets;
    for (int e : blocks.order) {
      const auto& ed = model.stretch.edges[e];
      const double damping =
          static_cast<std::size_t>(e) < model.stretch.damping.size() ? model.stretch.damping[e] : 0.0;
      out.stretch.push_back(
          {ed[0], ed[1], float(model.stretch.rest_length[e]), float(model.stretch.compliance[e]), float(damping)});
    }
  }
  if (model.bend.size() > 0) {
    const graph::ColorBlocks blocks = color<4>(model.bend.stencils, movable);
    out.bend_blocks = blocks.offsets;
    for (int e : blocks.order) {
      ats_bend_c c{};
      for (int k = 0; k < 4; ++k) {
        c.v[k] = model.bend.stencils[e][k];
        c.K[k] = float(model.bend.weights[e][k]);
      }
      c.scale = float(model.bend.scale[e]);
      c.compliance = float(model.bend.compliance[e]);
      c.rest_angle = float(model.bend.rest_angle[e]);
      c.model = model.bend.kind[e] == model::BendKind::dihedral ? ATS_BEND_DIHEDRAL : ATS_BEND_ISOMETRIC;
      out.bend.push_back(c);
    }
  }
  if (model.tets.size() > 0) {
    // Grouped by color like the other sets: XPBD sweeps them block by block;
    // the vertex-block methods only gather them and do not mind the order.
    const graph::ColorBlocks blocks = color<4>(model.tets.tets, movable);
    out.tet_blocks = blocks.offsets;
    for (int t : blocks.order) {
      if (model.tets.energy[t] == model::TetEnergy::springs) {
        // The model stage turns spring solids into stretch springs (model/tet_builder).
        throw internal_error("a spring solid reached the layout as tetrahedra; the model stage makes them springs");
      }
      ats_tet_c c{};
      for (int k = 0; k < 4; ++k) c.v[k] = model.tets.tets[t][k];
      const auto& m = model.tets.rest_inverse[t];
      for (int r = 0; r < 3; ++r) {
        for (int col = 0; col < 3; ++col) c.dm_inv[3 * r + col] = float(m(r, col));
      }
      c.volume = float(model.tets.rest_volume[t]);
      c.mu = float(model.tets.mu[t]);
      c.lambda = float(model.tets.lambda[t]);
      c.model = model.tets.energy[t] == model::TetEnergy::stvk ? ATS_TET_STVK : ATS_TET_NEO_HOOKEAN;
      out.tets.push_back(c);
    }
  }
  return out;
}

bool has_spring_damping(const SimLayout& layout) {
  for (const ats_distance_c& c : layout.stretch) {
    if (c.damping > 0.0f) return true;
  }
  return false;
}

float velocity_damping(const SimLayout& layout, double h) {
  return layout.air_drag > 0.0f ? static_cast<float>(1.0 / (1.0 + double(layout.air_drag) * h)) : 1.0f;
}

double inertia_dt(const SimLayout& layout, double h) {
  return layout.air_drag > 0.0f ? h / std::sqrt(1.0 + double(layout.air_drag) * h) : h;
}

}  // namespace atssim::solver
