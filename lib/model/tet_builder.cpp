#include "model/tet_builder.hpp"

#include <algorithm>
#include <cmath>

#include <fmt/format.h>
#include <Eigen/LU>

#include "model/object_particles.hpp"
#include "model/tet_box.hpp"
#include "model/tet_geometry.hpp"
#include "util/error.hpp"

namespace atssim::model {

namespace {

// A tet is degenerate when |V| ≤ kFlat · L³ (L its longest edge): a regular
// tet has V ≈ 0.118 L³, so this only catches vertices coplanar to rounding.
constexpr double kFlat = 1e-12;

TetEnergy energy_of(scene::SolidModel m) {
  switch (m) {
    case scene::SolidModel::stvk:
      return TetEnergy::stvk;
    case scene::SolidModel::springs:
      return TetEnergy::springs;
    case scene::SolidModel::neo_hookean:
      break;
  }
  return TetEnergy::neo_hookean;
}

double longest_edge(const std::array<Vec3, 4>& x) {
  double l = 0.0;
  for (int a = 0; a < 4; ++a) {
    for (int b = a + 1; b < 4; ++b) l = std::max(l, (x[a] - x[b]).norm());
  }
  return l;
}

[[noreturn]] void fail_element(const scene::TetMesh& mesh, std::size_t e, const scene::ObjectDesc& obj,
                               const std::string& scene_file, const std::string& what, const std::string& fix) {
  if (!mesh.file.empty() && e < mesh.element_line.size()) {
    throw input_error(
        fmt::format("{}:{}: element {} {}; {}", mesh.file, mesh.element_line[e], mesh.element_label[e], what, fix));
  }
  throw input_error(
      fmt::format("{}:{}: element {} of object '{}' {}; {}", scene_file, obj.source_line, e, obj.name, what, fix));
}

// A tetrahedral mass-spring body (seed 001): one spring per unique tet edge,
// stiffness k = E · L₀ (N/m; a bar of section L₀² and length L₀), in the
// stretch set every method simulates.
void add_tet_springs(Model& model, const scene::TetMesh& mesh, const ObjectRange& range, double youngs_modulus,
                     double damping) {
  std::vector<std::array<int, 2>> edges;
  edges.reserve(6 * mesh.tetrahedra.size());
  for (const auto& t : mesh.tetrahedra) {
    for (int a = 0; a < 4; ++a) {
      for (int b = a + 1; b < 4; ++b) edges.push_back({std::min(t[a], t[b]), std::max(t[a], t[b])});
    }
  }
  std::sort(edges.begin(), edges.end());
  edges.erase(std::unique(edges.begin(), edges.end()), edges.end());
  const int offset = range.vertex_offset;
  for (const auto& e : edges) {
    const double rest = (range.rest_position[e[0]] - range.rest_position[e[1]]).norm();
    model.stretch.add(e[0] + offset, e[1] + offset, rest, 1.0 / (youngs_modulus * rest), damping);
  }
}

}  // namespace

LameParameters lame_parameters(double youngs_modulus, double poisson_ratio) {
  const double E = youngs_modulus, nu = poisson_ratio;
  return {E / (2.0 * (1.0 + nu)), E * nu / ((1.0 + nu) * (1.0 - 2.0 * nu))};
}

std::vector<double> checked_volumes(scene::TetMesh& mesh, const std::vector<Vec3>& rest, const scene::ObjectDesc& obj,
                                    const std::string& scene_file) {
  std::vector<double> volume(mesh.tetrahedra.size());
  std::size_t negative = 0;
  for (std::size_t e = 0; e < mesh.tetrahedra.size(); ++e) {
    const auto& t = mesh.tetrahedra[e];
    const std::array<Vec3, 4> x{rest[t[0]], rest[t[1]], rest[t[2]], rest[t[3]]};
    volume[e] = signed_volume(x[0], x[1], x[2], x[3]);
    const double l = longest_edge(x);
    if (std::abs(volume[e]) <= kFlat * l * l * l) {
      fail_element(
          mesh, e, obj, scene_file,
          fmt::format("is degenerate (signed volume {:.3g}: its vertices are coplanar or repeated)", volume[e]),
          "remove it or fix the mesh");
    }
    if (volume[e] < 0.0) ++negative;
  }
  if (negative == volume.size()) {
    for (auto& t : mesh.tetrahedra) std::swap(t[2], t[3]);
    for (double& v : volume) v = -v;
    return volume;
  }
  for (std::size_t e = 0; e < volume.size(); ++e) {
    if (volume[e] < 0.0) {
      fail_element(mesh, e, obj, scene_file, fmt::format("is inverted (signed volume {:.3g})", volume[e]),
                   "fix the mesh or swap two of its vertices");
    }
  }
  return volume;
}

void add_solid(Model& model, const scene::ObjectDesc& obj, const std::string& scene_file) {
  scene::TetMesh mesh = obj.box ? make_tet_box(*obj.box) : obj.tet_mesh;
  ObjectRange range = begin_object(model, obj, mesh.vertices);
  check_placed(obj, range.rest_position, scene_file);
  const int offset = range.vertex_offset;
  const int n = range.vertex_count;
  const std::vector<double> volume = checked_volumes(mesh, range.rest_position, obj, scene_file);

  // Lumped masses: each tet gives a quarter of its mass to each corner.
  std::vector<double> mass(n, 0.0);
  for (std::size_t e = 0; e < mesh.tetrahedra.size(); ++e) {
    for (int v : mesh.tetrahedra[e]) mass[v] += obj.material.density * volume[e] / 4.0;
  }
  for (int v = 0; v < n; ++v) {
    if (!(mass[v] > 0.0) || !std::isfinite(mass[v])) {
      throw input_error(
          fmt::format("{}:{}: object '{}': node {} has no mass (it belongs to no tetrahedron); remove "
                      "unused nodes from the mesh",
                      scene_file, obj.source_line, obj.name, v));
    }
  }
  append_particles(model, range, mass, pinned_flags(obj, range.rest_position, scene_file));

  const TetEnergy energy = energy_of(obj.material.solid_model);
  if (energy == TetEnergy::springs) {
    add_tet_springs(model, mesh, range, obj.material.youngs_modulus, obj.material.damping);
    range.triangles = surface_triangles(mesh.tetrahedra);
    range.tetrahedra = std::move(mesh.tetrahedra);
    model.objects.push_back(std::move(range));
    return;
  }
  const LameParameters lame = lame_parameters(obj.material.youngs_modulus, obj.material.poisson_ratio);
  TetSet& tets = model.tets;
  for (std::size_t e = 0; e < mesh.tetrahedra.size(); ++e) {
    const auto& t = mesh.tetrahedra[e];
    const auto& x = range.rest_position;
    tets.tets.push_back({t[0] + offset, t[1] + offset, t[2] + offset, t[3] + offset});
    tets.rest_volume.push_back(volume[e]);
    tets.rest_inverse.push_back(rest_shape_matrix(x[t[0]], x[t[1]], x[t[2]], x[t[3]]).inverse());
    tets.mu.push_back(lame.mu);
    tets.lambda.push_back(lame.lambda);
    tets.energy.push_back(energy);
  }
  range.triangles = surface_triangles(mesh.tetrahedra);
  range.tetrahedra = std::move(mesh.tetrahedra);
  model.objects.push_back(std::move(range));
}

}  // namespace atssim::model
