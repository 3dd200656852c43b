#include "app/energy_growth.hpp"

#include <algorithm>
#include <cmath>

#include <fmt/format.h>

#include "solver/energy/element_energies.hpp"
#include "solver/energy/energy_plan.hpp"

namespace atssim::app {

namespace {

constexpr double kMinGravity = 9.81;  // m/s²: the energy scale of a scene without gravity

// The layout's particles and the elements with a finite energy.
solver::SimLayout energy_layout(const solver::SimLayout& in) {
  solver::SimLayout out;
  out.x = in.x;
  out.gravity = in.gravity;
  for (const ats_distance_c& c : in.stretch) {
    if (c.compliance > 0.0f) out.stretch.push_back(c);
  }
  for (const ats_bend_c& c : in.bend) {
    if (c.compliance > 0.0f) out.bend.push_back(c);
  }
  out.tets = in.tets;
  return out;
}

}  // namespace

EnergyGrowthCheck::EnergyGrowthCheck(const solver::SimLayout& layout, std::span<const float> velocities_xyz,
                                     std::span<const model::ObjectRange> objects, double factor)
    : layout_(factor > 0.0 ? energy_layout(layout) : solver::SimLayout{}), factor_(factor) {
  if (!enabled()) return;
  for (const model::ObjectRange& o : objects) objects_.push_back({o.name, o.vertex_offset, o.vertex_count});
  double lo[3] = {INFINITY, INFINITY, INFINITY}, hi[3] = {-INFINITY, -INFINITY, -INFINITY};
  double mass = 0.0, speed0 = 0.0;
  for (std::size_t i = 0; i < layout_.x.size(); ++i) {
    const solver::Float4& p = layout_.x[i];
    const double c[3] = {p.x, p.y, p.z};
    for (int k = 0; k < 3; ++k) {
      lo[k] = std::min(lo[k], c[k]);
      hi[k] = std::max(hi[k], c[k]);
    }
    if (p.w <= 0.0f) continue;
    mass += 1.0 / p.w;
    if (3 * i + 2 < velocities_xyz.size()) {
      const double v = std::hypot(velocities_xyz[3 * i], velocities_xyz[3 * i + 1], velocities_xyz[3 * i + 2]);
      if (std::isfinite(v)) speed0 = std::max(speed0, v);
    }
  }
  double d2 = 0.0;
  for (int k = 0; k < 3; ++k) d2 += hi[k] > lo[k] ? (hi[k] - lo[k]) * (hi[k] - lo[k]) : 0.0;
  const double size = std::max(std::sqrt(d2), 1e-3);
  const solver::Float4& g = layout_.gravity;
  const double gravity = std::max(std::hypot(double(g.x), double(g.y), double(g.z)), kMinGravity);
  scale_ = mass * (gravity * size + 0.5 * speed0 * speed0);
}

std::vector<float> EnergyGrowthCheck::terms(std::span<const float> xyz, std::span<const float> velocities_xyz) const {
  for (std::size_t i = 0; i < layout_.x.size() && 3 * i + 2 < xyz.size(); ++i) {
    layout_.x[i].x = xyz[3 * i];
    layout_.x[i].y = xyz[3 * i + 1];
    layout_.x[i].z = xyz[3 * i + 2];
  }
  // Predicted = x: the inertia terms are 0 and the particles' slots are free
  // for their kinetic energy.
  std::vector<float> out = solver::energy::element_energies(layout_, layout_.x, 1.0);
  for (std::size_t i = 0; i < layout_.x.size(); ++i) {
    const float w = layout_.x[i].w;
    out[i] = 0.0f;
    if (w > 0.0f && 3 * i + 2 < velocities_xyz.size()) {
      const double v2 = double(velocities_xyz[3 * i]) * velocities_xyz[3 * i] +
                        double(velocities_xyz[3 * i + 1]) * velocities_xyz[3 * i + 1] +
                        double(velocities_xyz[3 * i + 2]) * velocities_xyz[3 * i + 2];
      out[i] = static_cast<float>(0.5 * v2 / w);
    }
  }
  return out;
}

EnergyGrowthCheck::Energy EnergyGrowthCheck::energy(std::span<const float> xyz,
                                                    std::span<const float> velocities_xyz) const {
  Energy e;
  if (!enabled()) return e;
  const std::vector<float> t = terms(xyz, velocities_xyz);
  for (std::size_t i = 0; i < t.size(); ++i) (i < layout_.x.size() ? e.kinetic : e.elastic) += t[i];
  e.velocities.assign(velocities_xyz.begin(), velocities_xyz.end());
  return e;
}

std::optional<std::string> EnergyGrowthCheck::check(const Energy& before, std::span<const float> xyz_before,
                                                    const Energy& after, std::span<const float> xyz_after) {
  if (!enabled()) return std::nullopt;
  const solver::Float4& g = layout_.gravity;
  double work = 0.0;  // by gravity over the frame
  for (std::size_t i = 0; i < layout_.x.size() && 3 * i + 2 < xyz_after.size() && 3 * i + 2 < xyz_before.size(); ++i) {
    const float w = layout_.x[i].w;
    if (w <= 0.0f) continue;
    work += (g.x * (double(xyz_after[3 * i]) - xyz_before[3 * i]) +
             g.y * (double(xyz_after[3 * i + 1]) - xyz_before[3 * i + 1]) +
             g.z * (double(xyz_after[3 * i + 2]) - xyz_before[3 * i + 2])) /
            w;
  }
  const double base = std::max(before.total(), scale_);
  const double grown = after.total() - std::max(work, 0.0);
  const double ratio = std::isnan(grown) ? INFINITY : grown / base;
  largest_growth_ = std::max(largest_growth_, ratio);
  if (ratio <= factor_) return std::nullopt;

  // The element that exploded: the first object's element whose growth
  // alone passes the limit, else the one that grew most.
  const std::vector<float> was = terms(xyz_before, before.velocities), is = terms(xyz_after, after.velocities);
  const double limit = factor_ * base;
  std::size_t most = 0, first = is.size();
  double most_growth = -INFINITY;
  int first_object = static_cast<int>(objects_.size());
  for (std::size_t t = 0; t < is.size(); ++t) {
    const double growth = double(is[t]) - was[t];
    const double rank = std::isnan(growth) ? INFINITY : growth;
    if (rank > most_growth) {
      most_growth = rank;
      most = t;
    }
    if (rank > limit) {
      const int object = object_of(term_vertex(t));
      if (object < first_object) {
        first_object = object;
        first = t;
      }
    }
  }
  const std::size_t chosen = first < is.size() ? first : most;
  return fmt::format(
      "kinetic and elastic energy grew from {:.3g} J to {:.3g} J in the frame (gravity did {:.3g} J of work), more "
      "than simulation.energy_growth_limit {:g} times {:.3g} J allows; first in {} ({:.3g} J to {:.3g} J)",
      before.total(), after.total(), work, factor_, base, describe_term(chosen), was[chosen], is[chosen]);
}

int EnergyGrowthCheck::term_vertex(std::size_t term) const {
  const solver::energy::EnergyOutput at = solver::energy::energy_output(layout_);
  const auto t = static_cast<int>(term);
  if (t < at.stretch_first) return t;
  if (t < at.bend_first) return layout_.stretch[t - at.stretch_first].a;
  if (t < at.tet_first) return layout_.bend[t - at.bend_first].v[0];
  return layout_.tets[t - at.tet_first].v[0];
}

int EnergyGrowthCheck::object_of(int vertex) const {
  for (std::size_t k = 0; k < objects_.size(); ++k) {
    if (vertex >= objects_[k].vertex_offset && vertex < objects_[k].vertex_offset + objects_[k].vertex_count) {
      return static_cast<int>(k);
    }
  }
  return static_cast<int>(objects_.size());
}

std::string EnergyGrowthCheck::describe_term(std::size_t term) const {
  const solver::energy::EnergyOutput at = solver::energy::energy_output(layout_);
  const auto t = static_cast<int>(term);
  const int object = object_of(term_vertex(term));
  const bool known = object < static_cast<int>(objects_.size());
  const std::string name = known ? fmt::format("object '{}'", objects_[object].name) : std::string("the scene");
  const int offset = known ? objects_[object].vertex_offset : 0;
  const auto local = [&](int v) { return v - offset; };
  if (t < at.stretch_first) return fmt::format("{}, vertex {} (its kinetic energy)", name, local(t));
  if (t < at.bend_first) {
    const ats_distance_c& c = layout_.stretch[t - at.stretch_first];
    return fmt::format("{}, the stretch element between vertices {} and {}", name, local(c.a), local(c.b));
  }
  if (t < at.tet_first) {
    const ats_bend_c& c = layout_.bend[t - at.bend_first];
    return fmt::format("{}, the bending element over vertices {}, {}, {}, {}", name, local(c.v[0]), local(c.v[1]),
                       local(c.v[2]), local(c.v[3]));
  }
  const ats_tet_c& c = layout_.tets[t - at.tet_first];
  return fmt::format("{}, the tetrahedron with vertices {}, {}, {}, {}", name, local(c.v[0]), local(c.v[1]),
                     local(c.v[2]), local(c.v[3]));
}

}  // namespace atssim::app
