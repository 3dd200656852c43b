// The small variants of the paper's five scenes (scenes/paper/*_small.yaml,
// He et al. 2025 Table 1: dress, jersey, pillows, funnel, letters), end to
// end: a few frames under every method on one of the two CPU sub-devices,
// and one method per scene under HEFT on both (one test case per scene). At the last frame an independent checker
// (colliders read from the scene file and measured here in double, the surfaces by tests/support/surface_checks.hpp)
// asks for finite positions, no vertex deeper than 1 % of a collider's thickness inside it, and no surface edge through
// a triangle.
#include <catch2/catch.hpp>

#include <algorithm>
#include <array>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <initializer_list>
#include <map>
#include <sstream>
#include <string>
#include <utility>
#include <vector>

#include <yaml-cpp/yaml.h>
#include <Eigen/Core>
#include <Eigen/Geometry>

#include "app/simulation.hpp"
#include "model/cloth_builder.hpp"
#include "scene/scene_loader.hpp"
#include "support/methods.hpp"
#include "support/obstacle_meshes.hpp"
#include "support/scene_runs.hpp"
#include "support/surface_checks.hpp"
#include "support/temp_dir.hpp"

using namespace atssim;
using Eigen::Matrix3d;
using Eigen::Vector3d;

namespace {

// Frames and substeps per frame of the tests' runs (the scenes ask for 32
// or 64 substeps; 8 keeps the runs within a few minutes on 2 cores).
// Each scene starts within a few cm of contact; the pillows' cloth falls
// with them at first, so they meet it from frame 8 (XPBD: 1 vertex-triangle
// pair within the thickness at frame 8, 29 at frame 12).
constexpr int kSubsteps = 8;
int frames_of(const std::string& name) { return name == "pillows" ? 12 : 3; }

std::string scene_path(const std::string& name) {
  return std::string(ATSSIM_SOURCE_DIR) + "/scenes/paper/" + name + "_small.yaml";
}

Vector3d vec(const YAML::Node& n) { return Vector3d(n[0].as<double>(), n[1].as<double>(), n[2].as<double>()); }

// Degrees about x, then y, then z (docs/scene-format.md).
Matrix3d euler(const Vector3d& deg) {
  const double r = M_PI / 180.0;
  return (Eigen::AngleAxisd(deg.z() * r, Vector3d::UnitZ()) * Eigen::AngleAxisd(deg.y() * r, Vector3d::UnitY()) *
          Eigen::AngleAxisd(deg.x() * r, Vector3d::UnitX()))
      .toRotationMatrix();
}

test::SimpleMesh read_obj(const std::string& path) {
  test::SimpleMesh m;
  std::ifstream in(path);
  REQUIRE(in.good());
  std::string line;
  while (std::getline(in, line)) {
    std::istringstream s(line);
    std::string tag;
    s >> tag;
    if (tag == "v") {
      std::array<double, 3> v{};
      s >> v[0] >> v[1] >> v[2];
      m.vertices.push_back(v);
    } else if (tag == "f") {
      std::array<int, 3> f{};
      s >> f[0] >> f[1] >> f[2];
      m.triangles.push_back({f[0] - 1, f[1] - 1, f[2] - 1});
    }
  }
  return m;
}

// Every edge in exactly two triangles: the mesh has an inside.
bool closed(const test::SimpleMesh& m) {
  std::map<std::pair<int, int>, int> uses;
  for (const auto& t : m.triangles) {
    for (int k = 0; k < 3; ++k) ++uses[std::minmax(t[k], t[(k + 1) % 3])];
  }
  return std::all_of(uses.begin(), uses.end(), [](const auto& e) { return e.second == 2; });
}

// Inside a closed mesh: an odd number of its triangles cross a long ray.
bool inside(const test::SimpleMesh& m, const Vector3d& p) {
  const Vector3d far = p + 100.0 * Vector3d(0.5377, 0.8125, 0.2241).normalized();
  const auto at = [&](int i) { return Vector3d(m.vertices[i][0], m.vertices[i][1], m.vertices[i][2]); };
  int crossings = 0;
  for (const auto& t : m.triangles) crossings += test::segment_crosses(p, far, at(t[0]), at(t[1]), at(t[2]));
  return crossings % 2 == 1;
}

// A collider of the scene file, posed at a time, and its signed distance
// (negative inside) in its own frame.
struct Collider {
  std::string name, type;
  double thickness = 0.005, radius = 0.0;
  Vector3d pivot = Vector3d::Zero(), a, b, size, normal;  // a, b: the capsule's ends about its pivot
  Matrix3d base = Matrix3d::Identity();                   // a box's or mesh's own rotation
  double scale = 1.0;
  test::SimpleMesh mesh;
  bool is_closed = false;
  std::vector<std::pair<double, std::pair<Vector3d, double>>> keys;  // time, (position, turn about y in degrees)

  std::pair<Vector3d, Matrix3d> pose(double t) const {
    if (keys.empty()) return {pivot, Matrix3d::Identity()};
    if (t <= keys.front().first) return {keys.front().second.first, euler({0, keys.front().second.second, 0})};
    for (std::size_t k = 1; k < keys.size(); ++k) {
      if (t > keys[k].first) continue;
      const double s = (t - keys[k - 1].first) / (keys[k].first - keys[k - 1].first);
      const Vector3d p = (1 - s) * keys[k - 1].second.first + s * keys[k].second.first;
      const double yaw = (1 - s) * keys[k - 1].second.second + s * keys[k].second.second;
      return {p, euler({0, yaw, 0})};
    }
    return {keys.back().second.first, euler({0, keys.back().second.second, 0})};
  }

  double distance(const Vector3d& world, double t) const {
    const auto [at, turn] = pose(t);
    const Vector3d q = base.transpose() * turn.transpose() * (world - at);
    if (type == "sphere") return q.norm() - radius;
    if (type == "capsule") return test::point_segment(q, a, b) - radius;
    if (type == "plane") return q.dot(normal);
    if (type == "box") {
      const Vector3d d = q.cwiseAbs() - size / 2;
      return d.cwiseMax(0.0).norm() + std::min(d.maxCoeff(), 0.0);
    }
    const double d = test::mesh_distance(mesh, Vector3d::Zero(), q / scale) * scale;
    return is_closed && inside(mesh, q / scale) ? -d : d;
  }
};

std::vector<Collider> colliders_of(const std::string& path) {
  const YAML::Node scene = YAML::LoadFile(path);
  std::vector<Collider> out;
  for (const YAML::Node& n : scene["colliders"]) {
    Collider c;
    c.type = n["type"].as<std::string>();
    c.name = n["name"] ? n["name"].as<std::string>() : c.type;
    if (n["thickness"]) c.thickness = n["thickness"].as<double>();
    if (n["radius"]) c.radius = n["radius"].as<double>();
    // This checker poses keyframed colliders turning about y only.
    REQUIRE(!n["velocity"]);
    REQUIRE(!n["angular_velocity"]);
    if (c.type == "sphere" || c.type == "box") c.pivot = vec(n["center"]);
    if (c.type == "box") {
      c.size = vec(n["size"]);
      if (n["rotate"]) c.base = euler(vec(n["rotate"]));
    }
    if (c.type == "capsule") {
      c.pivot = (vec(n["a"]) + vec(n["b"])) / 2;
      c.a = vec(n["a"]) - c.pivot;
      c.b = vec(n["b"]) - c.pivot;
    }
    if (c.type == "plane") {
      c.pivot = n["point"] ? vec(n["point"]) : Vector3d::Zero();
      c.normal = n["normal"] ? vec(n["normal"]).normalized() : Vector3d::UnitY();
    }
    if (c.type == "mesh") {
      c.pivot = n["position"] ? vec(n["position"]) : Vector3d::Zero();
      if (n["rotation"]) c.base = euler(vec(n["rotation"]));
      if (n["scale"]) c.scale = n["scale"].as<double>();
      c.mesh = read_obj((std::filesystem::path(path).parent_path() / n["file"].as<std::string>()).string());
      c.is_closed = closed(c.mesh);
    }
    for (const YAML::Node& k : n["keyframes"]) {
      const Vector3d turn = k["rotation"] ? vec(k["rotation"]) : Vector3d::Zero();
      REQUIRE(turn.x() == 0.0);
      REQUIRE(turn.z() == 0.0);
      c.keys.push_back({k["time"].as<double>(), {vec(k["position"]), turn.y()}});
    }
    out.push_back(std::move(c));
  }
  return out;
}

struct Deepest {
  double fraction = -1e9;  // (thickness - signed distance) / thickness; > 0: inside the thickened surface
  std::string where;
};

void check_scene(const std::string& name, const std::string& method, const std::string& schedule) {
  INFO(name << " " << method << "/" << schedule);
  const std::string path = scene_path(name);
  test::TempDir dir;
  app::RunOptions o;
  o.scene_path = path;
  o.overrides = {"output.path=" + dir.file("out.h5"),
                 "devices=cpu/2",
                 "solver.method=" + method,
                 "solver.schedule=" + schedule,
                 "simulation.frames=" + std::to_string(frames_of(name)),
                 "simulation.substeps=" + std::to_string(kSubsteps),
                 "solver.wait_timeout=600"};  // a loaded machine can stall the fused executor's 10 s watchdog
  app::run_simulation(o);
  const std::vector<Vector3d> x = test::frame(dir.file("out.h5"), frames_of(name));
  REQUIRE(std::all_of(x.begin(), x.end(), [](const Vector3d& p) { return p.allFinite(); }));

  const YAML::Node scene = YAML::LoadFile(path);
  const double time = frames_of(name) / scene["simulation"]["fps"].as<double>();
  Deepest deepest;
  for (const Collider& c : colliders_of(path)) {
    for (std::size_t i = 0; i < x.size(); ++i) {
      const double fraction = 1.0 - c.distance(x[i], time) / c.thickness;
      if (fraction > deepest.fraction) deepest = {fraction, c.name + ", vertex " + std::to_string(i)};
    }
  }
  INFO("deepest vertex " << deepest.fraction << " of the thickness inside " << deepest.where);
  CHECK(deepest.fraction <= 0.01);
  if (scene["simulation"]["ground"]) {
    const double ground = scene["simulation"]["ground"].as<double>();
    double lowest = 1e9;
    for (const Vector3d& p : x) lowest = std::min(lowest, p.y());
    CHECK(lowest >= ground - 0.01 * scene["contact"]["thickness"].as<double>());
  }

  const double thickness = scene["contact"]["thickness"].as<double>();
  const test::Surface surface = test::surface_of(model::build_model(scene::load_scene_file(path)));
  const test::SurfaceReport r = test::check_surface(surface, x, 2 * thickness);
  INFO("closest non-incident vertex-triangle pair " << r.closest << " m (thickness " << thickness << "); "
                                                    << r.crossings << " edges through triangles");
  CHECK(r.crossings == 0);
  CHECK(r.closest >= 0.5 * thickness);
}

}  // namespace

TEST_CASE("the surface checker finds crossings and close pairs over a whole surface", "[paper]") {
  // Two triangles of one surface, two of the second's edges through the first.
  test::Surface s;
  s.tris = {{0, 1, 2}, {3, 4, 5}};
  s.edges = {{0, 1}, {1, 2}, {0, 2}, {3, 4}, {4, 5}, {3, 5}};
  std::vector<Vector3d> x = {{0, 0, 0}, {1, 0, 0}, {0, 0, 1}, {0.2, -0.1, 0.2}, {0.2, 0.1, 0.2}, {0.3, 0.1, 0.3}};
  test::SurfaceReport r = test::check_surface(s, x, 0.2);
  CHECK(r.crossings == 2);                    // edges 3-4 and 3-5 pass through the first triangle
  CHECK(r.closest == Approx(0.1));            // vertex 3 or 4 below/above the first triangle
  for (int i : {3, 4, 5}) x[i].y() += 0.104;  // the lowest 4 mm above
  r = test::check_surface(s, x, 0.05);
  CHECK(r.crossings == 0);
  CHECK(r.closest == Approx(0.004));
}

TEST_CASE("the collider checker measures a box turned by keyframes and the inside of a closed mesh", "[paper]") {
  test::TempDir dir;
  test::write_obj(dir.file("ball.obj"), test::obstacle_icosphere(0.1, 2));
  const std::string yaml =
      "colliders:\n"
      "  - {type: box, center: [0, 0, 0], size: [0.4, 0.2, 0.2],\n"
      "     keyframes: [{time: 0, position: [0, 0, 0]}, {time: 1, position: [1, 0, 0], rotation: [0, 90, 0]}]}\n"
      "  - {type: mesh, file: ball.obj, position: [0, 2, 0]}\n";
  const std::vector<Collider> c = colliders_of(dir.write("c.yaml", yaml));
  REQUIRE(c.size() == 2);
  // At t = 0.5 the box is at x = 0.5, turned by 45 degrees about y.
  const Vector3d along = euler({0, 45, 0}) * Vector3d(0.3, 0, 0);
  CHECK(c[0].distance(Vector3d(0.5, 0, 0) + along, 0.5) == Approx(0.1));
  CHECK(c[0].distance(Vector3d(0.5, 0, 0), 0.5) == Approx(-0.1));
  CHECK(c[0].distance(Vector3d(1.3, 0, 0), 1.0) == Approx(0.2));  // its long side along z at the end
  CHECK(c[1].is_closed);
  CHECK(c[1].distance(Vector3d(0, 2.05, 0), 0.0) < -0.04);
  CHECK(c[1].distance(Vector3d(0, 2.15, 0), 0.0) > 0.04);
}

namespace {

// One test case per scene (each its own ctest entry). Every method with contact on one device, and one method (a
// different one per scene) under HEFT on the two sub-devices: with contact every method gives the same bits on one
// device and cut over two (tests/app/test_self_contact.cpp), so the other HEFT runs would repeat the single runs'
// checks, at two to three times their cost (issue 24: CI time).
void check_every_method(const std::string& name, const char* heft_method) {
  for (const std::string& method :
       test::methods_where([](const solver::MethodDescription& m) { return m.colliders; })) {
    check_scene(name, method, "single");
  }
  check_scene(name, heft_method, "heft");
}

}  // namespace

TEST_CASE("the paper's dress, small, under every method, and XPBD under heft", "[paper][contact]") {
  check_every_method("dress", "xpbd");
}

// JPGD and VBD failed this (a vertex 1-2 % of the thickness inside the
// rising torso box) until the step out of the colliders came after the
// clamps of a substep's moves instead of before them (the clamp could put a
// vertex back inside).
TEST_CASE("the paper's jersey, small, under every method, and VBD under heft", "[paper][contact]") {
  check_every_method("jersey", "vbd");
}

TEST_CASE("the paper's pillows, small, under every method, and VBD under heft", "[paper][contact]") {
  check_every_method("pillows", "vbd");
}

TEST_CASE("the paper's funnel, small, under every method, and SOSD under heft", "[paper][contact]") {
  check_every_method("funnel", "sosd");
}

TEST_CASE("the paper's letters, small, under every method, and JPGD under heft", "[paper][contact]") {
  check_every_method("letters", "jpgd");
}
