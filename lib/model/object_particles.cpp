#include "model/object_particles.hpp"

#include <numbers>

#include <fmt/format.h>
#include <Eigen/Geometry>

#include "util/error.hpp"

namespace atssim::model {

namespace {

Eigen::Matrix3d rotation_xyz_deg(const scene::Vec3& deg) {
  const double k = std::numbers::pi / 180.0;
  return (Eigen::AngleAxisd(deg[2] * k, Vec3::UnitZ()) * Eigen::AngleAxisd(deg[1] * k, Vec3::UnitY()) *
          Eigen::AngleAxisd(deg[0] * k, Vec3::UnitX()))
      .toRotationMatrix();
}

}  // namespace

ObjectRange begin_object(const Model& model, const scene::ObjectDesc& obj,
                         const std::vector<std::array<double, 3>>& vertices) {
  ObjectRange range;
  range.name = obj.name;
  range.vertex_offset = static_cast<int>(model.particles.size());
  range.vertex_count = static_cast<int>(vertices.size());
  range.rest_position = place_vertices(obj.transform, vertices);
  if (obj.material.has_friction) range.friction = {obj.material.static_friction, obj.material.kinetic_friction};
  return range;
}

void check_placed(const scene::ObjectDesc& obj, const std::vector<Vec3>& placed, const std::string& scene_file) {
  for (std::size_t v = 0; v < placed.size(); ++v) {
    const Vec3& p = placed[v];
    if (!p.allFinite() || p.cwiseAbs().maxCoeff() > 1e8) {
      throw input_error(
          fmt::format("{}:{}: object '{}': vertex {} is at ({:g}, {:g}, {:g}) after the transform, not "
                      "finite or further than 1e8 m from the origin; fix the mesh, scale or translate",
                      scene_file, obj.source_line, obj.name, v, p.x(), p.y(), p.z()));
    }
  }
}

std::vector<Vec3> place_vertices(const scene::TransformDesc& transform,
                                 const std::vector<std::array<double, 3>>& vertices) {
  const Eigen::Matrix3d R = rotation_xyz_deg(transform.rotate_deg);
  const Vec3 scale(transform.scale[0], transform.scale[1], transform.scale[2]);
  const Vec3 translate(transform.translate[0], transform.translate[1], transform.translate[2]);
  std::vector<Vec3> placed;
  placed.reserve(vertices.size());
  for (const auto& v : vertices) placed.push_back(R * Vec3(v[0], v[1], v[2]).cwiseProduct(scale) + translate);
  return placed;
}

std::vector<char> pinned_flags(const scene::ObjectDesc& obj, const std::vector<Vec3>& rest_position,
                               const std::string& scene_file) {
  const int n = static_cast<int>(rest_position.size());
  std::vector<char> pinned(n, 0);
  for (int v : obj.pins.vertices) {
    if (v >= n) {
      throw input_error(
          fmt::format("{}:{}: pinned vertex {} is out of range: object '{}' has {} vertices "
                      "(0 to {}); fix the index",
                      scene_file, obj.source_line, v, obj.name, n, n - 1));
    }
    pinned[v] = 1;
  }
  for (const auto& box : obj.pins.boxes) {
    int hits = 0;
    for (int v = 0; v < n; ++v) {
      const Vec3& p = rest_position[v];
      bool inside = true;
      for (int k = 0; k < 3; ++k) inside = inside && p[k] >= box.min[k] && p[k] <= box.max[k];
      if (inside) {
        pinned[v] = 1;
        ++hits;
      }
    }
    if (hits == 0) {
      throw input_error(
          fmt::format("{}:{}: a pin box of object '{}' contains no vertex; boxes are in world "
                      "coordinates after the transform — enlarge or move it",
                      scene_file, obj.source_line, obj.name));
    }
  }
  return pinned;
}

void append_particles(Model& model, ObjectRange& range, const std::vector<double>& mass,
                      const std::vector<char>& pinned) {
  const int n = static_cast<int>(range.rest_position.size());
  for (int v = 0; v < n; ++v) {
    model.particles.position.push_back(range.rest_position[v]);
    model.particles.velocity.push_back(Vec3::Zero());
    model.particles.mass.push_back(mass[v]);
    const bool fixed = pinned[v] != 0 || mass[v] <= 0.0;
    model.particles.inv_mass.push_back(fixed ? 0.0 : 1.0 / mass[v]);
    if (pinned[v] != 0) range.pinned.push_back(v);
  }
}

}  // namespace atssim::model
