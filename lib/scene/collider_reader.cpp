#include "scene/collider_reader.hpp"

#include <cmath>

#include <fmt/format.h>

#include "scene/friction_reader.hpp"
#include "scene/kinematic_reader.hpp"
#include "scene/obstacle_reader.hpp"
#include "util/did_you_mean.hpp"

namespace atssim::scene {

namespace {

constexpr std::array<std::string_view, 5> kShapes{"plane", "sphere", "capsule", "box", "mesh"};
constexpr std::array<std::string_view, 5> kCommonKeys{"name", "type", "thickness", "friction", "stiffness"};

std::vector<std::string_view> keys_of(ColliderShape shape) {
  std::vector<std::string_view> keys(kCommonKeys.begin(), kCommonKeys.end());
  keys.insert(keys.end(), kMotionKeys.begin(), kMotionKeys.end());
  switch (shape) {
    case ColliderShape::plane:
      keys.insert(keys.end(), {"point", "normal"});
      break;
    case ColliderShape::sphere:
      keys.insert(keys.end(), {"center", "radius"});
      break;
    case ColliderShape::capsule:
      keys.insert(keys.end(), {"a", "b", "radius"});
      break;
    case ColliderShape::box:
      keys.insert(keys.end(), {"center", "size", "rotate"});
      break;
    case ColliderShape::mesh:
      keys.insert(keys.end(), {"file", "scale", "position", "rotation"});
      break;
  }
  return keys;
}

const char* shape_name(ColliderShape shape) { return kShapes[static_cast<int>(shape)].data(); }

ColliderShape read_shape(const YamlReader& r) {
  if (!r.has("type")) r.fail("a collider without 'type'", "add type: plane, sphere, capsule, box or mesh");
  const YamlReader t = r.child("type");
  const std::string name = t.string();
  for (std::size_t k = 0; k < kShapes.size(); ++k) {
    if (name == kShapes[k]) return static_cast<ColliderShape>(k);
  }
  const std::string guess = closest_match(name, kShapes);
  t.fail(fmt::format("unknown collider type '{}'", name), guess.empty()
                                                              ? std::string("use plane, sphere, capsule, box or mesh")
                                                              : fmt::format("did you mean '{}'?", guess));
}

double positive(const YamlReader& r, std::string_view what) {
  const double v = r.number();
  if (!(v > 0.0) || v > 1e6) {
    r.fail(fmt::format("'{}' is {}, but a {} must be positive", r.path(), r.node().Scalar(), what),
           fmt::format("give the {} in metres, e.g. 0.1", what));
  }
  return v;
}

}  // namespace

ColliderDesc read_collider(const YamlReader& r, int index, const std::filesystem::path& base_dir) {
  ColliderDesc c;
  c.source_line = r.line();
  if (!r.node().IsMap())
    r.fail("a collider should be a map of keys", "write e.g. {type: sphere, center: [0, 0, 0], radius: 0.3}");
  c.shape = read_shape(r);
  const std::vector<std::string_view> keys = keys_of(c.shape);
  r.expect_map(keys);
  c.name = r.has("name") ? r.child("name").string() : fmt::format("{}{}", shape_name(c.shape), index);
  if (r.has("thickness")) c.thickness = positive(r.child("thickness"), "thickness");
  if (r.has("friction")) {
    const FrictionDesc f = read_friction(r.child("friction"));
    c.static_friction = f.static_coefficient;
    c.kinetic_friction = f.kinetic_coefficient;
    c.friction_set = true;
  }
  if (r.has("stiffness")) {
    c.stiffness = r.child("stiffness").number_in(0.0, 1e6, true, "a contact stiffness relative to m/h², e.g. 100");
  }
  const auto require = [&](std::string_view key, std::string_view example) {
    if (!r.has(key))
      r.fail(fmt::format("a {} collider needs '{}'", shape_name(c.shape), key), fmt::format("add {}", example));
    return r.child(key);
  };
  switch (c.shape) {
    case ColliderShape::plane: {
      if (r.has("point")) c.point = r.child("point").vec3();
      if (r.has("normal")) {
        c.normal = r.child("normal").vec3();
        const double len = std::hypot(c.normal[0], c.normal[1], c.normal[2]);
        if (!(len > 1e-12)) r.child("normal").fail("the plane's normal is zero", "give a direction, e.g. [0, 1, 0]");
      }
      break;
    }
    case ColliderShape::sphere:
      c.point = require("center", "center: [x, y, z]").vec3();
      c.radius = positive(require("radius", "radius: 0.3"), "radius");
      break;
    case ColliderShape::capsule:
      c.point = require("a", "a: [x, y, z] (one end of its axis)").vec3();
      c.end = require("b", "b: [x, y, z] (the other end of its axis)").vec3();
      c.radius = positive(require("radius", "radius: 0.1"), "radius");
      break;
    case ColliderShape::box: {
      c.point = require("center", "center: [x, y, z]").vec3();
      const YamlReader size = require("size", "size: [sx, sy, sz] (full extents in metres)");
      c.size = size.vec3();
      for (double s : c.size) {
        if (!(s > 0.0))
          size.fail("a box's size must be positive along every axis", "give full extents in metres, e.g. [1, 0.5, 1]");
      }
      if (r.has("rotate")) c.rotate_deg = r.child("rotate").vec3();
      break;
    }
    case ColliderShape::mesh:
      read_mesh_obstacle(r, c, base_dir);
      break;
  }
  c.motion = read_motion(r);
  return c;
}

void emit_collider(YAML::Emitter& out, const ColliderDesc& c) {
  const auto vec = [&](const char* key, const std::array<double, 3>& v) {
    out << YAML::Key << key << YAML::Value << YAML::Flow << YAML::BeginSeq << v[0] << v[1] << v[2] << YAML::EndSeq;
  };
  out << YAML::BeginMap << YAML::Key << "name" << YAML::Value << c.name;
  out << YAML::Key << "type" << YAML::Value << shape_name(c.shape);
  switch (c.shape) {
    case ColliderShape::plane:
      vec("point", c.point);
      vec("normal", c.normal);
      break;
    case ColliderShape::sphere:
      vec("center", c.point);
      out << YAML::Key << "radius" << YAML::Value << c.radius;
      break;
    case ColliderShape::capsule:
      vec("a", c.point);
      vec("b", c.end);
      out << YAML::Key << "radius" << YAML::Value << c.radius;
      break;
    case ColliderShape::box:
      vec("center", c.point);
      vec("size", c.size);
      vec("rotate", c.rotate_deg);
      break;
    case ColliderShape::mesh:
      emit_mesh_obstacle(out, c);
      break;
  }
  emit_motion(out, c.motion);
  out << YAML::Key << "thickness" << YAML::Value << c.thickness;
  if (c.friction_set) {
    out << YAML::Key << "friction" << YAML::Value << YAML::Flow << YAML::BeginMap << YAML::Key << "static"
        << YAML::Value << c.static_friction << YAML::Key << "kinetic" << YAML::Value << c.kinetic_friction
        << YAML::EndMap;
  }
  out << YAML::Key << "stiffness" << YAML::Value << c.stiffness;
  out << YAML::EndMap;
}

}  // namespace atssim::scene
