#include <catch2/catch.hpp>

#include <numeric>
#include <string>

#include <fmt/format.h>
#include <Eigen/Geometry>

#include "model/cloth_builder.hpp"
#include "model/tet_box.hpp"
#include "model/tet_builder.hpp"
#include "model/tet_geometry.hpp"
#include "scene/scene_loader.hpp"
#include "support/temp_dir.hpp"
#include "util/error.hpp"

using namespace atssim;

namespace {

model::Model box_model(int nx, int ny, int nz, const std::string& extra = "") {
  const std::string yaml = fmt::format(
      "objects:\n  - name: jelly\n    type: solid\n    box: {{size: [0.3, 0.5, 0.7], resolution: [{}, {}, {}]}}\n"
      "    transform: {{translate: [1, 2, 3], rotate: [10, 20, 30]}}\n"
      "    material: {{density: 800, youngs_modulus: 1.0e5, poisson_ratio: 0.3}}\n{}",
      nx, ny, nz, extra);
  return model::build_model(scene::parse_scene(yaml, "s.yaml", "."));
}

double sum(const std::vector<double>& v) { return std::accumulate(v.begin(), v.end(), 0.0); }

// The unit cube as 5 tets, written as a 1-based TetGen pair; `tets` replaces the element lines.
std::string write_cube(const test::TempDir& dir, const std::string& tets) {
  dir.write("cube.node", "8 3 0 0\n1 0 0 0\n2 1 0 0\n3 0 1 0\n4 1 1 0\n5 0 0 1\n6 1 0 1\n7 0 1 1\n8 1 1 1\n");
  dir.write("cube.ele", tets);
  return dir.write("cube.yaml", "objects:\n  - name: cube\n    type: solid\n    mesh: cube.ele\n");
}

const std::string kCubeTets = "5 4 0\n1 1 2 3 5\n2 4 2 8 3\n3 6 2 5 8\n4 7 3 8 5\n5 2 3 5 8\n";

std::string build_error(const std::string& scene_path) {
  try {
    model::build_model(scene::load_scene_file(scene_path));
  } catch (const Error& e) {
    CHECK(e.exit_code() == 2);
    return e.what();
  }
  return "";
}

}  // namespace

TEST_CASE("the procedural box has the volume of its size and mass density times volume") {
  const auto m = box_model(3, 4, 5);
  CHECK(m.tets.size() == 6 * 3 * 4 * 5);
  CHECK(m.particles.size() == 4 * 5 * 6);
  const double volume = 0.3 * 0.5 * 0.7;
  CHECK(std::abs(sum(m.tets.rest_volume) - volume) <= 1e-12 * volume);
  CHECK(sum(m.particles.mass) == Approx(800 * volume).epsilon(1e-12));
}

TEST_CASE("every procedural tet is positively oriented and Dm⁻¹ inverts its rest shape") {
  const auto m = box_model(2, 3, 2);
  for (std::size_t e = 0; e < m.tets.size(); ++e) {
    const auto& t = m.tets.tets[e];
    const auto& x = m.particles.position;
    const double v = model::signed_volume(x[t[0]], x[t[1]], x[t[2]], x[t[3]]);
    CHECK(v > 0.0);
    CHECK(m.tets.rest_volume[e] == Approx(v));
    const Eigen::Matrix3d dm = model::rest_shape_matrix(x[t[0]], x[t[1]], x[t[2]], x[t[3]]);
    CHECK((m.tets.rest_inverse[e] * dm - Eigen::Matrix3d::Identity()).norm() < 1e-12);
  }
}

TEST_CASE("the box surface has 2 triangles per boundary cell face, all facing out") {
  const int nx = 3, ny = 2, nz = 4;
  const auto m = box_model(nx, ny, nz);
  const auto& obj = m.objects.at(0);
  CHECK(obj.tetrahedra.size() == 6u * nx * ny * nz);
  CHECK(obj.triangles.size() == 2u * 2 * (nx * ny + ny * nz + nx * nz));
  // Divergence theorem with F(x) = x / 3: Σ area·n · centroid / 3 = volume,
  // and every oriented edge has its reverse (a closed, consistently wound surface).
  double flux = 0.0;
  std::vector<std::pair<int, int>> edges;
  for (const auto& t : obj.triangles) {
    const auto& a = obj.rest_position[t[0]];
    const auto& b = obj.rest_position[t[1]];
    const auto& c = obj.rest_position[t[2]];
    flux += 0.5 * (b - a).cross(c - a).dot((a + b + c) / 3.0) / 3.0;
    for (int k = 0; k < 3; ++k) edges.emplace_back(t[k], t[(k + 1) % 3]);
  }
  CHECK(flux == Approx(0.3 * 0.5 * 0.7).epsilon(1e-12));
  std::sort(edges.begin(), edges.end());
  for (const auto& [u, v] : edges) CHECK(std::binary_search(edges.begin(), edges.end(), std::make_pair(v, u)));
}

TEST_CASE("Lamé parameters follow the textbook formulas") {
  const auto l = model::lame_parameters(1.0e5, 0.3);
  CHECK(l.mu == Approx(1.0e5 / (2 * 1.3)));
  CHECK(l.lambda == Approx(1.0e5 * 0.3 / (1.3 * 0.4)));
  const auto zero = model::lame_parameters(2.0e6, 0.0);
  CHECK(zero.mu == Approx(1.0e6));
  CHECK(zero.lambda == 0.0);
  const auto m = box_model(1, 1, 1);
  CHECK(m.tets.mu[0] == Approx(l.mu));
  CHECK(m.tets.lambda[5] == Approx(l.lambda));
  CHECK(m.tets.energy[0] == model::TetEnergy::neo_hookean);
}

TEST_CASE("a solid adds tets and no cloth element sets, and pins work as for cloth") {
  // The box's bottom face (y = -0.25 before the transform) is not axis-aligned
  // after it, so pin by vertex index: the first (nx+1) vertices are one edge.
  const auto m = box_model(2, 2, 2, "    pins: {vertices: [0, 1, 2]}\n");
  CHECK(m.stretch.size() == 0);
  CHECK(m.bend.size() == 0);
  CHECK(m.objects[0].pinned == std::vector<int>{0, 1, 2});
  CHECK(m.particles.inv_mass[2] == 0.0);
  CHECK(m.particles.inv_mass[3] > 0.0);
  CHECK_THROWS_WITH(box_model(1, 1, 1, "    pins: {vertices: [8]}\n"),
                    Catch::Contains("pinned vertex 8 is out of range"));
}

TEST_CASE("a tet mesh file builds with its volume, and cloth and solids share one particle array") {
  test::TempDir dir;
  const std::string path = write_cube(dir, kCubeTets);
  dir.write("both.yaml",
            "objects:\n  - grid: {size: [1, 1], resolution: [3, 3]}\n"
            "  - {type: solid, mesh: cube.node, material: {density: 2}}\n");
  const auto m = model::build_model(scene::load_scene_file(dir.file("both.yaml")));
  CHECK(m.particles.size() == 9 + 8);
  CHECK(m.objects[1].vertex_offset == 9);
  CHECK(m.tets.tets[0] == std::array<int, 4>{9, 10, 11, 13});
  CHECK(sum(m.tets.rest_volume) == Approx(1.0));
  CHECK(m.objects[1].triangles.size() == 12);  // the cube's 6 faces, 2 triangles each
  (void)path;
}

TEST_CASE("an inverted tet is reported by its file line and number") {
  test::TempDir dir;
  const std::string path = write_cube(dir, "5 4 0\n1 1 2 3 5\n2 4 2 8 3\n3 6 2 5 8\n4 7 3 5 8\n5 2 3 5 8\n");
  const std::string msg = build_error(path);
  CHECK(msg.find(dir.file("cube.ele") + ":5: element 4 is inverted (signed volume -0.167)") == 0);
  CHECK(msg.find("swap two of its vertices") != std::string::npos);
}

TEST_CASE("a degenerate tet is reported by its file line and number") {
  test::TempDir dir;
  const std::string path = write_cube(dir, "6 4 0\n1 1 2 3 5\n2 4 2 8 3\n3 6 2 5 8\n4 7 3 8 5\n5 2 3 5 8\n6 1 2 4 3\n");
  const std::string msg = build_error(path);
  CHECK(msg.find(dir.file("cube.ele") + ":7: element 6 is degenerate (signed volume 0") == 0);
}

TEST_CASE("a mesh written with the opposite vertex order is flipped, not rejected") {
  test::TempDir dir;
  const std::string path = write_cube(dir, "5 4 0\n1 1 2 5 3\n2 4 2 3 8\n3 6 2 8 5\n4 7 3 5 8\n5 2 3 8 5\n");
  const auto m = model::build_model(scene::load_scene_file(path));
  for (double v : m.tets.rest_volume) CHECK(v > 0.0);
  CHECK(sum(m.tets.rest_volume) == Approx(1.0));
}

TEST_CASE("a bad element of a procedural mesh is named by index and the object's scene line") {
  scene::ObjectDesc obj;
  obj.name = "blob";
  obj.source_line = 12;
  scene::TetMesh mesh{{{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0, 0, 1}}, {{0, 1, 2, 3}, {0, 2, 1, 3}}, "", {}, {}};
  const std::vector<model::Vec3> rest{{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0, 0, 1}};
  CHECK_THROWS_WITH(model::checked_volumes(mesh, rest, obj, "s.yaml"),
                    Catch::StartsWith("s.yaml:12: element 1 of object 'blob' is inverted"));
}
