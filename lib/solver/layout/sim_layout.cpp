#include "solver/layout/sim_layout.hpp"

#include <cmath>

#include "util/error.hpp"

namespace atssim::solver {

static_assert(sizeof(ats_collider_c) == 128, "the collider record is 32 floats in kernels and host");
static_assert(static_cast<int>(scene::ColliderShape::plane) == ATS_COLLIDER_PLANE &&
                  static_cast<int>(scene::ColliderShape::sphere) == ATS_COLLIDER_SPHERE &&
                  static_cast<int>(scene::ColliderShape::capsule) == ATS_COLLIDER_CAPSULE &&
                  static_cast<int>(scene::ColliderShape::box) == ATS_COLLIDER_BOX,
              "ColliderShape is in ATS_COLLIDER_* order");

namespace {

template <int Arity, typename Element>
graph::ColorBlocks color(const std::vector<Element>& elements, const std::vector<char>& movable) {
  std::vector<int> flat;
  flat.reserve(elements.size() * Arity);
  for (const auto& e : elements) flat.insert(flat.end(), e.begin(), e.end());
  return graph::color_elements(flat, Arity, movable);
}

void put(float* out, const Eigen::Vector3d& v) {
  for (int k = 0; k < 3; ++k) out[k] = float(v[k]);
  out[3] = 0.0f;
}

}  // namespace

std::vector<ats_collider_c> collider_records(const std::vector<model::Collider>& colliders) {
  std::vector<ats_collider_c> out;
  for (const model::Collider& c : colliders) {
    ats_collider_c r{};
    r.shape = float(static_cast<int>(c.shape));  // scene::ColliderShape follows ATS_COLLIDER_* order
    r.thickness = float(c.thickness);
    r.mu_s = float(c.static_friction);
    r.mu_k = float(c.kinetic_friction);
    put(r.c, c.point);
    put(r.n, c.shape == scene::ColliderShape::capsule ? c.end : c.normal);
    for (int k = 0; k < 3; ++k) put(r.axes + 4 * k, c.axes.row(k).transpose());
    put(r.extent, c.half);
    r.radius = float(c.radius);
    r.stiffness = float(c.stiffness);
    out.push_back(r);
  }
  return out;
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
  out.colliders = collider_records(model.colliders);
  out.self_contact = make_self_contact_layout(model);

  if (model.stretch.size() > 0) {
    const graph::ColorBlocks blocks = color<2>(model.stretch.edges, movable);
    out.stretch_blocks = blocks.offsets;
    for (int e : blocks.order) {
      const auto& ed = model.stretch.edges[e];
      out.stretch.push_back({ed[0], ed[1], float(model.stretch.rest_length[e]), float(model.stretch.compliance[e])});
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
        throw input_error("solids with model: springs are not simulated yet; use neo_hookean or stvk");
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

float velocity_damping(const SimLayout& layout, double h) {
  return layout.air_drag > 0.0f ? static_cast<float>(1.0 / (1.0 + double(layout.air_drag) * h)) : 1.0f;
}

double inertia_dt(const SimLayout& layout, double h) {
  return layout.air_drag > 0.0f ? h / std::sqrt(1.0 + double(layout.air_drag) * h) : h;
}

}  // namespace atssim::solver
