#include "model/contact_surface.hpp"

#include <limits>
#include <string>

#include <fmt/format.h>

#include "util/error.hpp"

namespace atssim::model {

std::optional<ContactSurface> make_contact_surface(const scene::SelfContactDesc& desc, const Model& model) {
  if (!desc.enabled) return std::nullopt;
  ContactSurface s;
  s.thickness = desc.thickness;
  s.stiffness = desc.stiffness;
  s.static_friction = desc.static_friction;
  s.kinetic_friction = desc.kinetic_friction;
  s.query_radius = desc.query_radius > 0.0 ? desc.query_radius : 3.0 * desc.thickness;
  double shortest = std::numeric_limits<double>::infinity();
  std::string shortest_object;
  for (const ObjectRange& o : model.objects) {
    for (const auto& t : o.triangles) {
      const std::array<int, 3> g{t[0] + o.vertex_offset, t[1] + o.vertex_offset, t[2] + o.vertex_offset};
      s.triangles.push_back(g);
      for (int k = 0; k < 3; ++k) {
        const double len = (model.particles.position[g[k]] - model.particles.position[g[(k + 1) % 3]]).norm();
        if (len < shortest) {
          shortest = len;
          shortest_object = o.name;
        }
      }
    }
  }
  if (!(s.thickness < 0.5 * shortest)) {
    throw input_error(
        fmt::format("{}: the contact thickness {} m is not below half the shortest surface edge ({:.4g} m, "
                    "object '{}'): triangles two rings apart would push each other away at rest; use a "
                    "thickness below {:.4g} or a coarser mesh",
                    desc.where, s.thickness, shortest, shortest_object, 0.5 * shortest));
  }
  return s;
}

}  // namespace atssim::model
