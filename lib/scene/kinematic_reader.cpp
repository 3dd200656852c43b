#include "scene/kinematic_reader.hpp"

#include <cmath>

#include <fmt/format.h>

namespace atssim::scene {

namespace {

constexpr std::array<std::string_view, 3> kKeyframeKeys{"time", "position", "rotation"};

std::array<double, 3> finite_vec3(const YamlReader& r, std::string_view what) {
  const std::array<double, 3> v = r.vec3();
  for (double x : v) {
    if (!std::isfinite(x) || std::abs(x) > 1e6) {
      r.fail(fmt::format("'{}' has a component {} out of range", r.path(), x),
             fmt::format("give the {} as three finite numbers", what));
    }
  }
  return v;
}

Keyframe read_keyframe(const YamlReader& r) {
  if (!r.node().IsMap()) r.fail("a keyframe should be a map", "write e.g. {time: 0.5, position: [0, 1, 0]}");
  r.expect_map(kKeyframeKeys);
  Keyframe k;
  k.source_line = r.line();
  if (!r.has("time")) r.fail("a keyframe without 'time'", "add time: seconds from the start");
  if (!r.has("position")) r.fail("a keyframe without 'position'", "add position: [x, y, z] (the collider's pivot)");
  k.time = r.child("time").number_in(0.0, 1e6, false, "a time in seconds >= 0");
  k.position = finite_vec3(r.child("position"), "position in metres");
  if (r.has("rotation")) k.rotation_deg = finite_vec3(r.child("rotation"), "rotation in degrees");
  return k;
}

}  // namespace

ColliderMotion read_motion(const YamlReader& r) {
  ColliderMotion m;
  const bool rate = r.has("velocity") || r.has("angular_velocity");
  if (rate && r.has("keyframes")) {
    r.child("keyframes")
        .fail("a collider has both keyframes and a velocity", "give either velocity/angular_velocity or keyframes");
  }
  if (rate) {
    m.kind = MotionKind::velocity;
    if (r.has("velocity")) m.velocity = finite_vec3(r.child("velocity"), "velocity in m/s");
    if (r.has("angular_velocity"))
      m.angular_velocity = finite_vec3(r.child("angular_velocity"), "angular velocity in rad/s");
    return m;
  }
  if (!r.has("keyframes")) return m;
  const YamlReader list = r.child("keyframes");
  const std::vector<YamlReader> keys = list.sequence();
  if (keys.empty()) list.fail("'keyframes' is empty", "give at least one {time, position}");
  m.kind = MotionKind::keyframes;
  for (const YamlReader& k : keys) {
    m.keyframes.push_back(read_keyframe(k));
    if (m.keyframes.size() > 1 && !(m.keyframes.back().time > m.keyframes[m.keyframes.size() - 2].time)) {
      k.child("time").fail(fmt::format("keyframe time {} does not come after the one before ({})",
                                       m.keyframes.back().time, m.keyframes[m.keyframes.size() - 2].time),
                           "list keyframes in increasing time");
    }
  }
  return m;
}

void emit_motion(YAML::Emitter& out, const ColliderMotion& m) {
  const auto vec = [&](const char* key, const std::array<double, 3>& v) {
    out << YAML::Key << key << YAML::Value << YAML::Flow << YAML::BeginSeq << v[0] << v[1] << v[2] << YAML::EndSeq;
  };
  if (m.kind == MotionKind::velocity) {
    vec("velocity", m.velocity);
    vec("angular_velocity", m.angular_velocity);
  }
  if (m.kind == MotionKind::keyframes) {
    out << YAML::Key << "keyframes" << YAML::Value << YAML::BeginSeq;
    for (const Keyframe& k : m.keyframes) {
      out << YAML::Flow << YAML::BeginMap << YAML::Key << "time" << YAML::Value << k.time;
      vec("position", k.position);
      vec("rotation", k.rotation_deg);
      out << YAML::EndMap;
    }
    out << YAML::EndSeq;
  }
}

}  // namespace atssim::scene
