#include "model/cloth_builder.hpp"

#include <algorithm>
#include <cmath>

#include <fmt/format.h>
#include <Eigen/Geometry>

#include "model/cloth_springs.hpp"
#include "model/contact_surface.hpp"
#include "model/object_particles.hpp"
#include "model/tet_builder.hpp"
#include "util/error.hpp"

namespace atssim::model {

scene::TriangleMesh make_grid_mesh(const scene::GridDesc& grid) {
  const int nx = grid.resolution[0];
  const int nz = grid.resolution[1];
  scene::TriangleMesh mesh;
  mesh.vertices.reserve(static_cast<std::size_t>(nx) * nz);
  for (int k = 0; k < nz; ++k) {
    for (int i = 0; i < nx; ++i) {
      const double x = grid.size[0] * (static_cast<double>(i) / (nx - 1) - 0.5);
      const double z = grid.size[1] * (static_cast<double>(k) / (nz - 1) - 0.5);
      mesh.vertices.push_back({x, 0.0, z});
    }
  }
  for (int k = 0; k + 1 < nz; ++k) {
    for (int i = 0; i + 1 < nx; ++i) {
      const int a = k * nx + i, b = a + 1, c = a + nx, d = c + 1;
      mesh.triangles.push_back({a, c, b});
      mesh.triangles.push_back({b, c, d});
    }
  }
  return mesh;
}

std::vector<std::array<int, 2>> unique_edges(const std::vector<std::array<int, 3>>& triangles) {
  std::vector<std::array<int, 2>> edges;
  edges.reserve(triangles.size() * 3);
  for (const auto& t : triangles) {
    for (int e = 0; e < 3; ++e) {
      const int a = t[e], b = t[(e + 1) % 3];
      edges.push_back({std::min(a, b), std::max(a, b)});
    }
  }
  std::sort(edges.begin(), edges.end());
  edges.erase(std::unique(edges.begin(), edges.end()), edges.end());
  return edges;
}

std::vector<std::array<int, 4>> bending_stencils(const std::vector<std::array<int, 3>>& triangles) {
  // Half-edges (min, max, opposite) sorted by edge: the two triangles of an
  // interior edge end up next to each other. A sort, not a map, keeps the
  // peak memory at 12 bytes per half-edge.
  std::vector<std::array<int, 3>> half;
  half.reserve(triangles.size() * 3);
  for (const auto& t : triangles) {
    for (int e = 0; e < 3; ++e) {
      const int a = t[e], b = t[(e + 1) % 3], c = t[(e + 2) % 3];
      half.push_back({std::min(a, b), std::max(a, b), c});
    }
  }
  std::sort(half.begin(), half.end());
  std::vector<std::array<int, 4>> stencils;
  for (std::size_t i = 0; i < half.size();) {
    std::size_t j = i;
    while (j < half.size() && half[j][0] == half[i][0] && half[j][1] == half[i][1]) ++j;
    // Boundary edges (1 triangle) bend nothing; non-manifold edges (> 2) are skipped.
    if (j - i == 2 && half[i][2] != half[i + 1][2]) {
      stencils.push_back({half[i][0], half[i][1], half[i][2], half[i + 1][2]});
    }
    i = j;
  }
  return stencils;
}

namespace {

double cot_between(const Vec3& a, const Vec3& b) { return a.dot(b) / a.cross(b).norm(); }

// Cotangent weights of the isometric bending model (Bergou et al. 2006, as
// in Bender's PositionBasedDynamics). Returns false for a degenerate stencil.
bool isometric_weights(const std::array<Vec3, 4>& x, std::array<double, 4>& K, double& scale) {
  const Vec3 e0 = x[1] - x[0], e1 = x[2] - x[0], e2 = x[3] - x[0], e3 = x[2] - x[1], e4 = x[3] - x[1];
  const double a0 = 0.5 * e0.cross(e1).norm();
  const double a1 = 0.5 * e0.cross(e2).norm();
  const double tiny = 1e-12 * std::max(1.0, e0.squaredNorm());
  if (a0 <= tiny || a1 <= tiny || e3.cross(e0).norm() <= tiny || e4.cross(e0).norm() <= tiny) return false;
  const double c01 = cot_between(e0, e1), c02 = cot_between(e0, e2);
  const double c03 = cot_between(-e0, e3), c04 = cot_between(-e0, e4);
  K = {c03 + c04, c01 + c02, -c01 - c03, -c02 - c04};
  scale = 3.0 / (a0 + a1);
  return true;
}

// The dihedral angle of a stencil as kernels/common/energy_dihedral.h
// measures it: 0 flat, in (−π, π].
double dihedral_angle(const std::array<Vec3, 4>& x) {
  const Vec3 e = x[1] - x[0];
  const Vec3 na = e.cross(x[2] - x[0]);
  const Vec3 nb = (x[3] - x[0]).cross(e);
  return std::atan2(nb.cross(na).dot(e) / e.norm(), na.dot(nb));
}

// 3/2 |e|² / (A0 + A1): the dihedral energy k · scale · θ² then equals the
// isometric ½ k · 3/(A0 + A1) · |Σ K_i x_i|² to second order for a small
// fold of a flat stencil (there |Σ K_i x_i| ≈ |e| θ).
double dihedral_scale(const std::array<Vec3, 4>& x) {
  const Vec3 e = x[1] - x[0];
  const double areas = 0.5 * (e.cross(x[2] - x[0]).norm() + (x[3] - x[0]).cross(e).norm());
  return 1.5 * e.squaredNorm() / areas;
}

// Rest angles above this make `bend_model: auto` choose the dihedral model.
constexpr double kFlatAngle = 1e-4;  // radians

void add_bending(Model& model, const scene::ObjectDesc& obj, const scene::TriangleMesh& mesh,
                 const ObjectRange& range) {
  struct Stencil {
    std::array<int, 4> v;
    std::array<Vec3, 4> x;
    std::array<double, 4> K;
    double scale;
    double angle;
  };
  std::vector<Stencil> stencils;
  bool curved = false;
  for (const auto& s : bending_stencils(mesh.triangles)) {
    Stencil st{s, {}, {}, 0.0, 0.0};
    for (int i = 0; i < 4; ++i) st.x[i] = range.rest_position[s[i]];
    if (!isometric_weights(st.x, st.K, st.scale)) continue;  // degenerate: bends nothing
    st.angle = dihedral_angle(st.x);
    curved = curved || std::abs(st.angle) > kFlatAngle;
    stencils.push_back(st);
  }
  const scene::BendModel choice = obj.material.bend_model;
  const bool dihedral = choice == scene::BendModel::dihedral || (choice == scene::BendModel::automatic && curved);
  const int offset = range.vertex_offset;
  for (const Stencil& st : stencils) {
    model.bend.stencils.push_back({st.v[0] + offset, st.v[1] + offset, st.v[2] + offset, st.v[3] + offset});
    model.bend.weights.push_back(dihedral ? std::array<double, 4>{} : st.K);
    model.bend.scale.push_back(dihedral ? dihedral_scale(st.x) : st.scale);
    model.bend.rest_angle.push_back(dihedral ? st.angle : 0.0);
    model.bend.kind.push_back(dihedral ? BendKind::dihedral : BendKind::isometric);
    model.bend.compliance.push_back(obj.material.bend_compliance);
  }
}

// `model: springs` (model/cloth_springs.hpp): structural springs take the
// stretch stiffness, shear and bending springs their own; all are stretch
// elements with the object's damping.
void add_cloth_springs(Model& model, const scene::ObjectDesc& obj, const scene::TriangleMesh& mesh,
                       const ObjectRange& range) {
  const scene::MaterialDesc& m = obj.material;
  const ClothSprings springs = obj.grid ? grid_springs(obj.grid->resolution[0], obj.grid->resolution[1])
                                        : mesh_springs(range.rest_position, mesh.triangles);
  const int offset = range.vertex_offset;
  const auto add = [&](const std::vector<std::array<int, 2>>& pairs, double compliance) {
    for (const auto& p : pairs) {
      const double rest = (range.rest_position[p[0]] - range.rest_position[p[1]]).norm();
      model.stretch.add(p[0] + offset, p[1] + offset, rest, compliance, m.damping);
    }
  };
  if (m.has_stretch) add(springs.structural, m.stretch_compliance);
  if (m.shear_stiffness > 0.0) add(springs.shear, 1.0 / m.shear_stiffness);
  if (m.bend_spring_stiffness > 0.0) add(springs.bend, 1.0 / m.bend_spring_stiffness);
}

void add_cloth(Model& model, const scene::ObjectDesc& obj, const scene::TriangleMesh& mesh,
               const std::string& scene_file) {
  ObjectRange range = begin_object(model, obj, mesh.vertices);
  const int offset = range.vertex_offset;
  const int n = range.vertex_count;
  range.triangles = mesh.triangles;

  check_placed(obj, range.rest_position, scene_file);
  std::vector<double> mass(n, 0.0);
  for (std::size_t k = 0; k < mesh.triangles.size(); ++k) {
    const auto& t = mesh.triangles[k];
    const Vec3& a = range.rest_position[t[0]];
    const Vec3 e1 = range.rest_position[t[1]] - a, e2 = range.rest_position[t[2]] - a;
    const double area = 0.5 * e1.cross(e2).norm();
    const double longest = std::max({e1.squaredNorm(), e2.squaredNorm(), (e2 - e1).squaredNorm()});
    if (!(area > 1e-12 * longest) || area == 0.0) {
      throw input_error(
          fmt::format("{}:{}: object '{}': triangle {} (vertices {}, {}, {}) has zero area (its corners "
                      "coincide or lie on a line), so it gives its vertices no mass; remove degenerate "
                      "faces from the mesh",
                      scene_file, obj.source_line, obj.name, k, t[0], t[1], t[2]));
    }
    for (int v : t) mass[v] += obj.material.density * area / 3.0;
  }
  for (int v = 0; v < n; ++v) {
    if (!(mass[v] > 0.0) || !std::isfinite(mass[v])) {
      throw input_error(
          fmt::format("{}:{}: object '{}': vertex {} has no mass (it belongs to no triangle, or the "
                      "density is 0); remove unused vertices from the mesh",
                      scene_file, obj.source_line, obj.name, v));
    }
  }

  append_particles(model, range, mass, pinned_flags(obj, range.rest_position, scene_file));

  if (obj.material.cloth_springs) {
    add_cloth_springs(model, obj, mesh, range);
  } else if (obj.material.has_stretch) {
    for (const auto& e : unique_edges(mesh.triangles)) {
      model.stretch.add(e[0] + offset, e[1] + offset, (range.rest_position[e[0]] - range.rest_position[e[1]]).norm(),
                        obj.material.stretch_compliance, obj.material.damping);
    }
  }
  if (obj.material.has_bending) add_bending(model, obj, mesh, range);
  model.objects.push_back(std::move(range));
}

}  // namespace

Model build_model(const scene::SceneDesc& scene) {
  Model model;
  model.gravity = Vec3(scene.simulation.gravity[0], scene.simulation.gravity[1], scene.simulation.gravity[2]);
  model.ground = scene.simulation.ground;
  model.air_drag = scene.simulation.air_drag;
  model.colliders = make_colliders(scene.colliders);
  for (const auto& obj : scene.objects) {
    if (obj.type == scene::ObjectType::solid) {
      add_solid(model, obj, scene.source_path);
      continue;
    }
    const scene::TriangleMesh mesh = obj.grid ? make_grid_mesh(*obj.grid) : obj.mesh;
    add_cloth(model, obj, mesh, scene.source_path);
  }
  model.contact_surface = make_contact_surface(scene.contact, model);
  return model;
}

}  // namespace atssim::model
