#include "scene/obstacle_reader.hpp"

#include <algorithm>
#include <cmath>

#include <fmt/format.h>

#include "scene/mesh_loader.hpp"

namespace atssim::scene {

namespace fs = std::filesystem;

void read_mesh_obstacle(const YamlReader& r, ColliderDesc& c, const fs::path& base_dir) {
  if (!r.has("file")) r.fail("a mesh collider needs 'file'", "add file: bowl.obj (relative to the scene file)");
  const YamlReader f = r.child("file");
  fs::path p(f.string());
  if (p.is_relative()) p = base_dir / p;
  c.file = p.lexically_normal().string();
  if (r.has("position")) c.point = r.child("position").vec3();
  if (r.has("rotation")) c.rotate_deg = r.child("rotation").vec3();
  if (r.has("scale")) {
    const YamlReader s = r.child("scale");
    c.scale = s.node().IsScalar() ? std::array<double, 3>{s.number(), s.number(), s.number()} : s.vec3();
    for (double v : c.scale) {
      if (!(v > 0.0) || v > 1e6) s.fail("a mesh's scale must be positive", "give scale: 1 or [sx, sy, sz] above 0");
    }
  }
  const TriangleMesh mesh = load_triangle_mesh(c.file, f.where());
  // Zero-area triangles have no normal; the obstacle drops them, and needs others.
  const auto area2 = [&](const std::array<int, 3>& t) {
    const auto& a = mesh.vertices[t[0]];
    const auto& b = mesh.vertices[t[1]];
    const auto& d = mesh.vertices[t[2]];
    const double u[3] = {b[0] - a[0], b[1] - a[1], b[2] - a[2]}, v[3] = {d[0] - a[0], d[1] - a[1], d[2] - a[2]};
    const double n[3] = {u[1] * v[2] - u[2] * v[1], u[2] * v[0] - u[0] * v[2], u[0] * v[1] - u[1] * v[0]};
    return n[0] * n[0] + n[1] * n[1] + n[2] * n[2];
  };
  if (std::none_of(mesh.triangles.begin(), mesh.triangles.end(), [&](const auto& t) { return area2(t) > 0.0; })) {
    f.fail(fmt::format("'{}' has no triangle of non-zero area", f.string()), "give a mesh with a surface");
  }
  c.mesh_vertices = mesh.vertices;
  c.mesh_triangles = mesh.triangles;
}

void emit_mesh_obstacle(YAML::Emitter& out, const ColliderDesc& c) {
  const auto vec = [&](const char* key, const std::array<double, 3>& v) {
    out << YAML::Key << key << YAML::Value << YAML::Flow << YAML::BeginSeq << v[0] << v[1] << v[2] << YAML::EndSeq;
  };
  out << YAML::Key << "file" << YAML::Value << c.file;
  vec("scale", c.scale);
  vec("position", c.point);
  vec("rotation", c.rotate_deg);
}

}  // namespace atssim::scene
