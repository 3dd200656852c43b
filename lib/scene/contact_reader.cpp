#include "scene/contact_reader.hpp"

#include <array>

#include <fmt/format.h>

#include "scene/friction_reader.hpp"

namespace atssim::scene {

namespace {

constexpr std::array<std::string_view, 6> kContactKeys{"self",         "thickness", "stiffness",
                                                       "query_radius", "friction",  "strict"};

// `contact.<key>`: true or false (false when absent).
bool read_flag(const YamlReader& r, const char* key) {
  if (!r.has(key)) return false;
  const YamlReader s = r.child(key);
  const std::string v = s.string();
  if (v != "true" && v != "false") s.fail(fmt::format("'contact.{}' is '{}'", key, v), "use true or false");
  return v == "true";
}

}  // namespace

SelfContactDesc read_self_contact(const YamlReader& r) {
  SelfContactDesc c;
  if (!r.node().IsMap())
    r.fail("'contact' should be a map of keys", "write e.g. contact: {self: true, thickness: 0.005}");
  r.expect_map(kContactKeys);
  c.where = r.where();
  c.enabled = read_flag(r, "self");
  c.strict = read_flag(r, "strict");
  if (r.has("thickness")) {
    c.thickness =
        r.child("thickness").number_in(0.0, 1.0, true, "a thickness in metres, 0 < thickness ≤ 1, e.g. 0.005");
  }
  if (r.has("stiffness")) {
    c.stiffness = r.child("stiffness").number_in(0.0, 1e6, true, "a contact stiffness relative to m/h², e.g. 100");
  }
  if (r.has("query_radius")) {
    const YamlReader q = r.child("query_radius");
    c.query_radius = q.number_in(0.0, 10.0, true, "a detection radius in metres, e.g. 3 × the thickness");
    if (c.query_radius < c.thickness) {
      q.fail(fmt::format("'contact.query_radius' {} is below the thickness {}", c.query_radius, c.thickness),
             "give a query radius of at least the thickness (default 3 × thickness)");
    }
  }
  if (r.has("friction")) {
    const FrictionDesc f = read_friction(r.child("friction"));
    c.static_friction = f.static_coefficient;
    c.kinetic_friction = f.kinetic_coefficient;
  }
  return c;
}

void emit_self_contact(YAML::Emitter& out, const SelfContactDesc& c) {
  if (!c.enabled) return;
  out << YAML::Key << "contact" << YAML::Value << YAML::BeginMap;
  out << YAML::Key << "self" << YAML::Value << true;
  out << YAML::Key << "thickness" << YAML::Value << c.thickness;
  out << YAML::Key << "stiffness" << YAML::Value << c.stiffness;
  out << YAML::Key << "query_radius" << YAML::Value << (c.query_radius > 0.0 ? c.query_radius : 3.0 * c.thickness);
  if (c.static_friction > 0.0 || c.kinetic_friction > 0.0) {
    out << YAML::Key << "friction" << YAML::Value << YAML::Flow << YAML::BeginMap;
    out << YAML::Key << "static" << YAML::Value << c.static_friction;
    out << YAML::Key << "kinetic" << YAML::Value << c.kinetic_friction;
    out << YAML::EndMap;
  }
  out << YAML::Key << "strict" << YAML::Value << c.strict;
  out << YAML::EndMap;
}

}  // namespace atssim::scene
