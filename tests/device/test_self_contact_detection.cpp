// The device's self-contact detection (kernels/contact/self_contact.cl: BVH
// refit and the three queries) against a brute force over the same surface
// on the host: the same nearest pairs, the same nearest distance, the same
// displacement bound.
#include <catch2/catch.hpp>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstring>
#include <random>
#include <string>

#include <Eigen/Core>
#include <Eigen/Geometry>

#include "device/device_set.hpp"
#include "device/plan_executor.hpp"
#include "model/cloth_builder.hpp"
#include "scene/scene_loader.hpp"
#include "solver/vbd/vbd_plan.hpp"

using namespace atssim;

namespace {

constexpr int kCapacity = 8, kStride = kCapacity + 2;

// Two layers 1.2 cm apart (within the 3 cm query radius) and a third far away.
const char* kScene =
    "simulation: {fps: 60, substeps: 1, iterations: 1, frames: 1, gravity: [0, 0, 0]}\n"
    "objects:\n"
    "  - {name: a, grid: {size: [0.3, 0.3], resolution: [7, 7]}, material: {density: 0.2, stretch_stiffness: 100}}\n"
    "  - {name: b, grid: {size: [0.3, 0.3], resolution: [6, 6]}, transform: {rotate: [0, 17, 0], translate: [0.01, "
    "0.012, 0.02]},\n"
    "     material: {density: 0.2, stretch_stiffness: 100}}\n"
    "  - {name: c, grid: {size: [0.3, 0.3], resolution: [5, 5]}, transform: {translate: [2, 0, 0]},\n"
    "     material: {density: 0.2, stretch_stiffness: 100}}\n"
    "contact: {self: true, thickness: 0.01}\n";

Eigen::Vector3d at(const std::vector<solver::Float4>& x, int i) { return {x[i].x, x[i].y, x[i].z}; }

double seg_param(const Eigen::Vector3d& p, const Eigen::Vector3d& a, const Eigen::Vector3d& b) {
  const Eigen::Vector3d ab = b - a;
  return std::clamp((p - a).dot(ab) / ab.squaredNorm(), 0.0, 1.0);
}

double seg_dist(const Eigen::Vector3d& p, const Eigen::Vector3d& a, const Eigen::Vector3d& b) {
  return (p - a - seg_param(p, a, b) * (b - a)).norm();
}

// Point-triangle: the closest point of the triangle to p, from its plane and
// its edges (independent of the kernels' closed form).
Eigen::Vector3d pt_closest(const Eigen::Vector3d& p, const Eigen::Vector3d& a, const Eigen::Vector3d& b,
                           const Eigen::Vector3d& c) {
  const Eigen::Vector3d m = (b - a).cross(c - a), n = m.normalized();
  Eigen::Vector3d q = p - (p - a).dot(n) * n;
  if ((b - a).cross(q - a).dot(m) >= 0 && (c - b).cross(q - b).dot(m) >= 0 && (a - c).cross(q - c).dot(m) >= 0)
    return q;
  Eigen::Vector3d best = a;
  for (const auto& [u, w] : {std::pair{a, b}, std::pair{b, c}, std::pair{c, a}}) {
    const Eigen::Vector3d on = u + seg_param(p, u, w) * (w - u);
    if ((p - on).norm() < (p - best).norm()) best = on;
  }
  return best;
}

double pt_dist(const Eigen::Vector3d& p, const Eigen::Vector3d& a, const Eigen::Vector3d& b, const Eigen::Vector3d& c) {
  return (p - pt_closest(p, a, b, c)).norm();
}

// Edge-edge: the offset between the closest points.
Eigen::Vector3d ee_offset(const Eigen::Vector3d& p0, const Eigen::Vector3d& p1, const Eigen::Vector3d& q0,
                          const Eigen::Vector3d& q1) {
  // The distance from p(s) to segment q is convex in s: ternary search.
  double lo = 0.0, hi = 1.0;
  const auto f = [&](double t) { return seg_dist(p0 + t * (p1 - p0), q0, q1); };
  for (int k = 0; k < 200; ++k) {
    const double m1 = lo + (hi - lo) / 3, m2 = hi - (hi - lo) / 3;
    if (f(m1) < f(m2)) {
      hi = m2;
    } else {
      lo = m1;
    }
  }
  const double s = f(0.0) < f(lo) ? 0.0 : f(1.0) < f(lo) ? 1.0 : lo;
  const Eigen::Vector3d p = p0 + s * (p1 - p0);
  return p - (q0 + seg_param(p, q0, q1) * (q1 - q0));
}

double ee_dist(const Eigen::Vector3d& p0, const Eigen::Vector3d& p1, const Eigen::Vector3d& q0,
               const Eigen::Vector3d& q1) {
  return ee_offset(p0, p1, q0, q1).norm();
}

// No contact pairs: primitives that share a vertex (incident), and sheet
// neighbours (tested on pairs within reach only, after the distance): a vertex of each corners of one triangle, the
// offset between the closest points within 30 degrees of the plane of the triangle (of every triangle of either edge).
struct Excluded {
  const solver::SelfContactLayout& s;
  const std::vector<solver::Float4>& x;
  std::vector<std::vector<int>> tris_of;  // per particle, its triangles

  Excluded(const solver::SelfContactLayout& layout, const std::vector<solver::Float4>& positions)
      : s(layout), x(positions), tris_of(positions.size()) {
    for (int t = 0; t < int(s.tris.size()); ++t)
      for (int k = 0; k < 3; ++k) tris_of[s.tris[t][k]].push_back(t);
  }
  bool joined(int v, std::initializer_list<int> others) const {
    for (int t : tris_of[v])
      for (int w : others)
        if (s.tris[t][0] == w || s.tris[t][1] == w || s.tris[t][2] == w) return true;
    return false;
  }
  bool in_plane(const Eigen::Vector3d& d, const std::array<int, 4>& t) const {
    const Eigen::Vector3d n = (at(x, t[1]) - at(x, t[0])).cross(at(x, t[2]) - at(x, t[0])).normalized();
    return std::abs(n.dot(d.normalized())) < 0.5;  // sin 30 degrees
  }
  bool edge_in_plane(const Eigen::Vector3d& d, const std::array<int, 2>& e) const {
    for (int t : tris_of[e[0]]) {
      const auto& f = s.tris[t];
      if ((f[0] == e[1] || f[1] == e[1] || f[2] == e[1]) && !in_plane(d, f)) return false;
    }
    return true;
  }
  bool vertex_triangle(int v, const std::array<int, 4>& f) const {
    if (v == f[0] || v == f[1] || v == f[2]) return true;
    const Eigen::Vector3d d = at(x, v) - pt_closest(at(x, v), at(x, f[0]), at(x, f[1]), at(x, f[2]));
    return joined(v, {f[0], f[1], f[2]}) && in_plane(d, f);
  }
  bool edge_edge(const std::array<int, 2>& a, const std::array<int, 2>& b) const {
    if (a[0] == b[0] || a[0] == b[1] || a[1] == b[0] || a[1] == b[1]) return true;
    const Eigen::Vector3d d = ee_offset(at(x, a[0]), at(x, a[1]), at(x, b[0]), at(x, b[1]));
    return (joined(a[0], {b[0], b[1]}) || joined(a[1], {b[0], b[1]})) && edge_in_plane(d, a) && edge_in_plane(d, b);
  }
};

// Incident pairs, which no list holds (cheap: tested before the distance).
bool incident(int v, const std::array<int, 4>& f) { return v == f[0] || v == f[1] || v == f[2]; }
bool incident(const std::array<int, 2>& a, const std::array<int, 2>& b) {
  return a[0] == b[0] || a[0] == b[1] || a[1] == b[0] || a[1] == b[1];
}

std::vector<int> ints_of(const std::vector<std::byte>& raw) {
  std::vector<int> out(raw.size() / 4);
  std::memcpy(out.data(), raw.data(), raw.size());
  return out;
}

plan::BufferId buffer_named(const plan::SubstepPlan& p, const std::string& name) {
  for (std::size_t b = 0; b < p.buffers.size(); ++b) {
    if (p.buffers[b].name == name) return static_cast<plan::BufferId>(b);
  }
  FAIL("no buffer " << name);
  return -1;
}

// The device list of element e against the brute force distances of its
// candidates (id, distance), nearest first. Whether more than the list
// holds were within the radius (it keeps the nearest).
bool check_list(const std::vector<int>& list, int e, std::vector<std::pair<double, int>> expected, float radius) {
  std::sort(expected.begin(), expected.end());
  const int* l = list.data() + e * kStride;
  INFO("element " << e << ": " << expected.size() << " within the radius");

  REQUIRE(l[0] == std::min<int>(kCapacity, int(expected.size())));
  // [1]: the horizon, the distance every unlisted candidate is at least at
  float horizon;
  std::memcpy(&horizon, &l[1], 4);
  CHECK(horizon == Approx(int(expected.size()) >= kCapacity ? expected[kCapacity - 1].first : radius).margin(2e-5));
  for (int k = 0; k < l[0]; ++k) {
    // The k-th device entry is one of the brute force's entries at (nearly) the k-th distance.
    const auto it = std::find_if(expected.begin(), expected.end(), [&](const auto& p) { return p.second == l[2 + k]; });
    REQUIRE(it != expected.end());
    CHECK(it->first == Approx(expected[k].first).margin(2e-5));
  }
  return int(expected.size()) > kCapacity;
}

// One detection (a frame's first substep, at contact.query_radius;
// common/self_contact_lists.h sc_decide) from `layout`'s positions, its
// lists against the brute force. Counts of vertex-triangle pairs within the
// radius: contact pairs, those of them joined by a triangle (folded), and
// sheet neighbours (not contact pairs).
struct PairCounts {
  int pairs = 0, folded = 0, sheet = 0, overfull = 0;  // overfull: lists that kept only the nearest
};

PairCounts check_detection(const solver::SimLayout& layout) {
  const solver::SelfContactLayout& s = layout.self_contact;
  REQUIRE(s.enabled);
  const plan::SubstepPlan plan = solver::vbd::make_vbd_plan(layout, 1.0 / 60.0, 1);
  const auto devices = device::DeviceSet::open("cpu");
  device::PlanExecutor exec(devices, plan, {});
  exec.run_substeps(1);
  const std::vector<int> vt = ints_of(exec.read(buffer_named(plan, "sc_vt")));
  const std::vector<int> tv = ints_of(exec.read(buffer_named(plan, "sc_tv")));
  const std::vector<int> ee = ints_of(exec.read(buffer_named(plan, "sc_ee")));
  const std::vector<int> state = ints_of(exec.read(buffer_named(plan, "sc_state")));
  CHECK(state[1] == 1);
  float radius = 0.0f;
  std::memcpy(&radius, &state[2], 4);
  CHECK(radius == s.query_radius);
  const auto& x = layout.x;  // detection runs on x_t, the substep's start
  const int n = int(x.size());
  const Excluded excluded(s, x);
  std::vector<char> surface(n, 0);
  for (const auto& t : s.tris) surface[t[0]] = surface[t[1]] = surface[t[2]] = 1;
  PairCounts c;
  for (int v = 0; v < n; ++v) {
    std::vector<std::pair<double, int>> expected;
    for (int t = 0; surface[v] && t < int(s.tris.size()); ++t) {
      const auto& f = s.tris[t];
      if (incident(v, f)) continue;
      const double d = pt_dist(at(x, v), at(x, f[0]), at(x, f[1]), at(x, f[2]));
      if (!(d < radius)) continue;
      if (excluded.vertex_triangle(v, f)) {
        ++c.sheet;
      } else {
        expected.emplace_back(d, t);
        c.folded += excluded.joined(v, {f[0], f[1], f[2]});
      }
    }
    c.pairs += int(expected.size());
    c.overfull += check_list(vt, v, expected, radius);
  }
  for (int t = 0; t < int(s.tris.size()); ++t) {
    const auto& f = s.tris[t];
    std::vector<std::pair<double, int>> expected;
    for (int v = 0; v < n; ++v) {
      if (!surface[v] || incident(v, f)) continue;
      const double d = pt_dist(at(x, v), at(x, f[0]), at(x, f[1]), at(x, f[2]));
      if (d < radius && !excluded.vertex_triangle(v, f)) expected.emplace_back(d, v);
    }
    c.overfull += check_list(tv, t, expected, radius);
  }
  for (int e = 0; e < int(s.edges.size()); ++e) {
    const auto& a = s.edges[e];
    std::vector<std::pair<double, int>> expected;
    for (int f = 0; f < int(s.edges.size()); ++f) {
      const auto& b = s.edges[f];
      if (incident(a, b)) continue;
      const double d = ee_dist(at(x, a[0]), at(x, a[1]), at(x, b[0]), at(x, b[1]));
      if (d < radius && !excluded.edge_edge(a, b)) expected.emplace_back(d, f);
    }
    c.overfull += check_list(ee, e, expected, radius);
  }
  return c;
}

// The layout of `scene` with every particle moved by up to `amplitude` along
// each axis (uniform, from `seed`): no two layers exactly parallel.
solver::SimLayout jittered_layout(const std::string& scene, unsigned seed, float amplitude) {
  solver::SimLayout layout = solver::make_sim_layout(model::build_model(scene::parse_scene(scene, "s.yaml", ".")));
  std::mt19937 rng(seed);
  std::uniform_real_distribution<float> u(-amplitude, amplitude);
  for (auto& p : layout.x) {
    p.x += u(rng);
    p.y += u(rng);
    p.z += u(rng);
  }
  return layout;
}

}  // namespace

TEST_CASE("self-contact detection on the device finds the brute force's nearest pairs and bound", "[self]") {
  const solver::SimLayout layout = jittered_layout(kScene, 3, 0.002f);
  CHECK(check_detection(layout).pairs > 100);  // the two layers do face each other
}

TEST_CASE("where more primitives than a list holds are within the radius, the device keeps the brute force's nearest",
          "[self]") {
  // kScene with a query radius of 8 cm: a vertex of one layer has more
  // than eight triangles of the other within it, so hundreds of lists
  // overflow, and each must hold the brute force's nearest eight, in
  // order, with the eighth's distance as its horizon (sc_list_insert's
  // eviction, sc_list_store).
  std::string scene = kScene;
  const std::string contact = "contact: {self: true, thickness: 0.01}";
  scene.replace(scene.find(contact), contact.size(), "contact: {self: true, thickness: 0.01, query_radius: 0.08}");
  const PairCounts c = check_detection(jittered_layout(scene, 5, 0.004f));
  CHECK(c.overfull > 100);
}

TEST_CASE("a sheet folded onto itself keeps its folded neighbours as contact pairs, not its flat ones", "[self]") {
  // One sheet, edges 6 cm, a query radius of 6 cm: in the flat part every
  // vertex has triangles of its neighbours within the radius, in the sheet's
  // plane (sheet neighbours, not listed); the part beyond x = 0 is folded up
  // by 100 degrees, so a vertex there and the flat triangles beside the fold
  // are joined but apart mostly along the flat part's normal (listed).
  const char* scene =
      "simulation: {fps: 60, substeps: 1, iterations: 1, frames: 1, gravity: [0, 0, 0]}\n"
      "objects:\n"
      "  - {name: a, grid: {size: [0.3, 0.3], resolution: [6, 6]}, material: {density: 0.2, stretch_stiffness: 100}}\n"
      "contact: {self: true, thickness: 0.012, query_radius: 0.06}\n";
  const model::Model m = model::build_model(scene::parse_scene(scene, "s.yaml", "."));
  solver::SimLayout layout = solver::make_sim_layout(m);
  const double fold = 100.0 * M_PI / 180.0;
  for (auto& p : layout.x) {
    if (p.x > 0.0f) {
      const double r = p.x;
      p.x = static_cast<float>(r * std::cos(fold));
      p.y = static_cast<float>(r * std::sin(fold));
    }
  }
  const PairCounts c = check_detection(layout);
  CHECK(c.folded > 0);
  CHECK(c.sheet > c.folded);
}

namespace {
// The upper layer of kScene sliding over the lower one, which is pinned,
// under a weak gravity.
model::Model sliding_layers() {
  std::string scene = kScene;
  scene.replace(scene.find("gravity: [0, 0, 0]"), 18, "gravity: [4, -1, 0]");
  const std::string a = "material: {density: 0.2, stretch_stiffness: 100}}\n";
  scene.replace(scene.find(a), a.size(),
                "material: {density: 0.2, stretch_stiffness: 100},\n"
                "     pins: {boxes: [{min: [-1, -0.01, -1], max: [1, 0.005, 1]}]}}\n");
  return model::build_model(scene::parse_scene(scene, "s.yaml", "."));
}
}  // namespace

TEST_CASE(
    "the lists are kept while the motion allows, and always hold every pair closer than 1.5 thicknesses at the "
    "substep's start",
    "[self][slow]") {  // [slow]: its brute force over 24 substeps took ~460 s under ASan (check.sh --quick skips it)
  // The upper layer of the scene above falling onto the lower one, pinned,
  // under a weak gravity, many substeps: early substeps move little and keep
  // the lists, later ones move more and rebuild them; the pairs change as
  // the layers close.
  const model::Model m = sliding_layers();
  const solver::SimLayout layout = solver::make_sim_layout(m);
  const solver::SelfContactLayout& s = layout.self_contact;
  const plan::SubstepPlan plan = solver::vbd::make_vbd_plan(layout, 1.0 / 60.0, 1);
  const auto devices = device::DeviceSet::open("cpu");
  device::PlanExecutor exec(devices, plan, {});
  const float near = 1.5f * s.thickness;
  const int substeps = 24;
  int kept = 0, checked = 0;
  for (int k = 0; k < substeps; ++k) {
    exec.run_substeps(1);
    const std::vector<int> state = ints_of(exec.read(buffer_named(plan, "sc_state")));
    if (state[1] == 0) ++kept;
    std::vector<solver::Float4> x(layout.x.size());
    const std::vector<std::byte> raw = exec.read(buffer_named(plan, "x_prev"));  // x_t of this substep
    std::memcpy(x.data(), raw.data(), raw.size());
    const Excluded excluded(s, x);
    const std::vector<int> vt = ints_of(exec.read(buffer_named(plan, "sc_vt")));
    const std::vector<int> ee = ints_of(exec.read(buffer_named(plan, "sc_ee")));
    for (int v = 0; v < int(x.size()); ++v) {
      for (int t = 0; t < int(s.tris.size()); ++t) {
        const auto& f = s.tris[t];
        if (incident(v, f) || pt_dist(at(x, v), at(x, f[0]), at(x, f[1]), at(x, f[2])) >= near) continue;
        if (excluded.vertex_triangle(v, f)) continue;
        const int* l = vt.data() + v * kStride;
        INFO("substep " << k << ": vertex " << v << ", triangle " << t);
        // listed, or the list is full of nearer ones (the 8 nearest are kept)
        CHECK((std::find(l + 2, l + 2 + l[0], t) != l + 2 + l[0] || l[0] == kCapacity));
        ++checked;
      }
    }
    for (int e = 0; e < int(s.edges.size()); ++e) {
      const auto& a = s.edges[e];
      for (int f = 0; f < int(s.edges.size()); ++f) {
        const auto& b = s.edges[f];
        if (incident(a, b) || ee_dist(at(x, a[0]), at(x, a[1]), at(x, b[0]), at(x, b[1])) >= near) continue;
        if (excluded.edge_edge(a, b)) continue;
        const int* l = ee.data() + e * kStride;
        INFO("substep " << k << ": edge " << e << ", edge " << f);
        CHECK((std::find(l + 2, l + 2 + l[0], f) != l + 2 + l[0] || l[0] == kCapacity));
        ++checked;
      }
    }
    if (k + 1 == substeps) {
      INFO(state[4] << " detections in " << substeps << " substeps, " << kept << " kept the lists");
      CHECK(state[4] + kept == substeps);
      CHECK(kept >= 2);      // early, slow substeps keep them
      CHECK(state[4] >= 2);  // and the motion makes them rebuild
    }
  }
  CHECK(checked > 100);
}

TEST_CASE("two layers falling as a whole keep their lists, and fall freely", "[self]") {
  // The two near layers of the scene above, and the far one, dropped with
  // one gravity and no pins, substeps of 1/60 s: every vertex moves by the
  // same vector, which changes no distance between primitives, so after the
  // first substep the lists are kept (common/self_contact_lists.h
  // sc_decide), although from the sixth substep on the layers have fallen
  // further since then than the query radius's slack, (3 r - 1.5 r) / 2 = 7.5 mm; and the bound (0.4 of
  // the 11-12 mm between the layers) truncates no step: each substep ends at
  // x_t + h v + h^2 g (discrete free fall, VBD's inertia).
  std::string scene = kScene;
  scene.replace(scene.find("gravity: [0, 0, 0]"), 18, "gravity: [0, -1.5, 0]");
  const model::Model m = model::build_model(scene::parse_scene(scene, "s.yaml", "."));
  const solver::SimLayout layout = solver::make_sim_layout(m);
  const double h = 1.0 / 60.0, g = 1.5;
  const plan::SubstepPlan plan = solver::vbd::make_vbd_plan(layout, h, 1);
  const auto devices = device::DeviceSet::open("cpu");
  device::PlanExecutor exec(devices, plan, {});
  std::vector<solver::Float4> x = layout.x;
  double v = 0.0;  // every vertex's downward speed
  for (int k = 0; k < 8; ++k) {
    exec.run_substeps(1);
    const std::vector<int> state = ints_of(exec.read(buffer_named(plan, "sc_state")));
    INFO("substep " << k);
    CHECK(state[1] == (k == 0 ? 1 : 0));
    v += g * h;
    std::vector<solver::Float4> next(x.size());
    const std::vector<std::byte> raw = exec.read(buffer_named(plan, "x"));
    std::memcpy(next.data(), raw.data(), raw.size());
    double worst = 0.0;
    for (std::size_t i = 0; i < x.size(); ++i)
      worst = std::max({worst, std::abs(next[i].y - (x[i].y - h * v)), double(std::abs(next[i].x - x[i].x)),
                        double(std::abs(next[i].z - x[i].z))});
    CHECK(worst < 1e-6);
    x = next;
  }
  CHECK(layout.x[0].y - x[0].y > 0.015);  // 1.5 / 3600 * 36 m
}

TEST_CASE("a run restored from its own state at every substep goes on with the lists it had, bit for bit", "[self]") {
  // The sliding upper layer of the scene above, twice: one executor runs
  // on, the other is reset from its own state (positions, velocities and the
  // carried lists, x_det, each block's rho there and the decision state, as
  // a checkpoint holds them)
  // before every substep. Both must stay equal, bit for bit, lists, state
  // and positions. Restored from positions and velocities alone, every
  // block makes its lists anew.
  const model::Model m = sliding_layers();
  const solver::SimLayout layout = solver::make_sim_layout(m);
  const solver::SelfContactLayout& s = layout.self_contact;
  const plan::SubstepPlan plan = solver::vbd::make_vbd_plan(layout, 1.0 / 60.0, 2);
  const auto devices = device::DeviceSet::open("cpu");
  device::PlanExecutor on(devices, plan, {}), restored(devices, plan, {}), fresh(devices, plan, {});
  const std::size_t n = layout.x.size(), tris = s.tris.size(), edges = s.edges.size();
  const std::size_t blocks = on.read(buffer_named(plan, "sc_block_rho0")).size() / 4;
  REQUIRE(blocks >= 1);
  // the lists and their packed counts, x_det (float4s), sc_state (8 ints), each block's rho0
  REQUIRE(on.carried_bytes() == (n + tris + edges) * (kStride + 1) * 4 + n * 16 + 8 * 4 + blocks * 4);
  int kept = 0, made = 0;
  for (int k = 0; k < 16; ++k) {
    on.run_substeps(1);
    const plan::PlanState state = restored.read_state();
    REQUIRE(state.carried.size() == restored.carried_bytes());
    restored.reset(state);
    restored.run_substeps(1);
    const std::vector<int> st = ints_of(restored.read(buffer_named(plan, "sc_state")));
    INFO("substep " << k);
    (st[1] == 0 ? kept : made) += 1;
    CHECK(ints_of(on.read(buffer_named(plan, "sc_vt"))) == ints_of(restored.read(buffer_named(plan, "sc_vt"))));
    CHECK(ints_of(on.read(buffer_named(plan, "sc_ee"))) == ints_of(restored.read(buffer_named(plan, "sc_ee"))));
    CHECK(on.read(buffer_named(plan, "x")) == restored.read(buffer_named(plan, "x")));
    CHECK(ints_of(on.read(buffer_named(plan, "sc_state"))) == st);
    CHECK(on.read(buffer_named(plan, "sc_block_rho0")) == restored.read(buffer_named(plan, "sc_block_rho0")));
    if (k == 5) {
      // From positions and velocities alone: every block makes its lists.
      plan::PlanState bare = on.read_state();
      bare.carried.clear();
      fresh.reset(bare);
      fresh.run_substeps(1);
      const std::vector<int> f = ints_of(fresh.read(buffer_named(plan, "sc_state")));
      CHECK(f[1] == 1);
      CHECK(f[5] == static_cast<int>(blocks));
    }
  }
  CHECK(kept >= 2);  // substeps that kept every list, restored from the state
  CHECK(made >= 2);  // and the motion made some anew
}
