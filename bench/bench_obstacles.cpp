// BVH of a triangle-mesh obstacle (lib/model/obstacle_bvh): rebuild against
// refit after the vertices moved, and what a nearest-triangle query within
// the contact reach costs through the kernels' header (common/mesh_contact.h,
// host float) against the brute-force loop over every triangle, the
// native reference a user would write first.
//
//   bench_obstacles [--levels 3,4,5,6] [--repeats 9]
//
// Prints one table row per icosphere size (medians of --repeats runs).
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <map>
#include <random>
#include <string>
#include <vector>

#include <fmt/format.h>
#include <CLI/CLI.hpp>

#include "common/collider_distance.h"
#include "model/collider.hpp"
#include "model/obstacle_bvh.hpp"
#include "solver/contact/collider_buffer.hpp"

using namespace atssim;
using Clock = std::chrono::steady_clock;

namespace {

struct Mesh {
  std::vector<std::array<double, 3>> v;
  std::vector<std::array<int, 3>> t;
};

Mesh icosphere(int levels) {
  const double g = (1.0 + std::sqrt(5.0)) / 2.0;
  Mesh m;
  m.v = {{-1, g, 0},  {1, g, 0},  {-1, -g, 0}, {1, -g, 0}, {0, -1, g},  {0, 1, g},
         {0, -1, -g}, {0, 1, -g}, {g, 0, -1},  {g, 0, 1},  {-g, 0, -1}, {-g, 0, 1}};
  m.t = {{0, 11, 5},  {0, 5, 1},  {0, 1, 7},  {0, 7, 10}, {0, 10, 11}, {1, 5, 9}, {5, 11, 4},
         {11, 10, 2}, {10, 7, 6}, {7, 1, 8},  {3, 9, 4},  {3, 4, 2},   {3, 2, 6}, {3, 6, 8},
         {3, 8, 9},   {4, 9, 5},  {2, 4, 11}, {6, 2, 10}, {8, 6, 7},   {9, 8, 1}};
  const auto unit = [](std::array<double, 3> p) {
    const double n = std::sqrt(p[0] * p[0] + p[1] * p[1] + p[2] * p[2]);
    return std::array<double, 3>{p[0] / n, p[1] / n, p[2] / n};
  };
  for (auto& p : m.v) p = unit(p);
  for (int l = 0; l < levels; ++l) {
    std::map<std::pair<int, int>, int> mid;
    const auto middle = [&](int a, int b) {
      const auto key = std::minmax(a, b);
      if (auto it = mid.find(key); it != mid.end()) return it->second;
      m.v.push_back(unit({m.v[a][0] + m.v[b][0], m.v[a][1] + m.v[b][1], m.v[a][2] + m.v[b][2]}));
      return mid[key] = static_cast<int>(m.v.size()) - 1;
    };
    std::vector<std::array<int, 3>> next;
    for (const auto& f : m.t) {
      const int a = middle(f[0], f[1]), b = middle(f[1], f[2]), c = middle(f[2], f[0]);
      next.insert(next.end(), {{f[0], a, c}, {f[1], b, a}, {f[2], c, b}, {a, b, c}});
    }
    m.t = next;
  }
  return m;
}

template <typename F>
double median_ms(int repeats, F&& f) {
  std::vector<double> ms;
  for (int r = 0; r < repeats; ++r) {
    const auto start = Clock::now();
    f();
    ms.push_back(std::chrono::duration<double, std::milli>(Clock::now() - start).count());
  }
  std::nth_element(ms.begin(), ms.begin() + ms.size() / 2, ms.end());
  return ms[ms.size() / 2];
}

}  // namespace

int main(int argc, char** argv) {
  CLI::App app{"BVH rebuild vs refit, and BVH vs brute-force queries"};
  std::vector<int> levels{3, 4, 5, 6};
  int repeats = 9;
  app.add_option("--levels", levels, "icosphere subdivision levels")->delimiter(',');
  app.add_option("--repeats", repeats, "runs per measurement (the median is printed)");
  CLI11_PARSE(app, argc, argv);

  std::printf(
      "| triangles | rebuild ms | refit ms | refit / rebuild | BVH query µs/point | brute force µs/point | brute / BVH "
      "|\n");
  std::printf("|---:|---:|---:|---:|---:|---:|---:|\n");
  std::mt19937 rng(5);
  for (int level : levels) {
    const Mesh mesh = icosphere(level);
    scene::ColliderDesc d;
    d.shape = scene::ColliderShape::mesh;
    d.mesh_vertices = mesh.v;
    d.mesh_triangles = mesh.t;
    d.thickness = 0.01;
    const std::vector<model::Collider> colliders = model::make_colliders({d});
    const model::ObstacleMesh& om = *colliders[0].mesh;

    // The vertices moved a little (a deforming surface): refit the tree, or build a new one.
    std::vector<Eigen::Vector3d> moved = om.vertices;
    std::normal_distribution<double> jitter(0.0, 1e-3);
    for (auto& p : moved) p += Eigen::Vector3d(jitter(rng), jitter(rng), jitter(rng));
    model::ObstacleBvh bvh = om.bvh;
    const double rebuild = median_ms(repeats, [&] { bvh = model::build_bvh(moved, om.triangles); });
    const double refit = median_ms(repeats, [&] { model::refit_bvh(bvh, moved, om.triangles); });

    // Query points in a shell around the unit sphere, half of them within the reach.
    const solver::ColliderBuffer buffer = solver::collider_buffer(colliders);
    const float reach = buffer.records[0].mesh[3];
    std::vector<ats_vec3> points;
    std::uniform_real_distribution<double> u(-1.0, 1.0), r(1.0 - reach, 1.0 + reach);
    for (int k = 0; k < 20000; ++k) {
      Eigen::Vector3d p(u(rng), u(rng), u(rng));
      p = p.normalized() * r(rng);
      points.push_back(ats_v3(float(p.x()), float(p.y()), float(p.z())));
    }
    float sink = 0.0f;
    const double bvh_ms = median_ms(repeats, [&] {
      for (const ats_vec3& p : points) sink += ats_collider_distance(buffer.records.data(), p).phi;
    });
    const std::size_t brute_points = std::min<std::size_t>(points.size(), 2000000 / om.triangles.size() + 1);
    const double brute_ms = median_ms(std::max(1, repeats / 3), [&] {
      for (std::size_t k = 0; k < brute_points; ++k) {
        float best = 1e30f;
        for (const auto& t : om.triangles) {
          int feature = 0;
          const auto& a = om.vertices[t[0]];
          const auto& b = om.vertices[t[1]];
          const auto& c = om.vertices[t[2]];
          const ats_vec3 q = ats_closest_on_triangle(points[k], ats_v3(float(a.x()), float(a.y()), float(a.z())),
                                                     ats_v3(float(b.x()), float(b.y()), float(b.z())),
                                                     ats_v3(float(c.x()), float(c.y()), float(c.z())), &feature);
          const ats_vec3 e = ats_sub(points[k], q);
          best = std::min(best, ats_dot(e, e));
        }
        sink += best;
      }
    });
    const double bvh_us = 1000.0 * bvh_ms / points.size(), brute_us = 1000.0 * brute_ms / brute_points;
    std::printf("| %zu | %.3f | %.3f | %.3f | %.3f | %.2f | %.0f |\n", om.triangles.size(), rebuild, refit,
                refit / rebuild, bvh_us, brute_us, brute_us / bvh_us);
    if (sink == 12345.0f) std::printf(" ");  // keeps the loops from being optimised away
  }
  return 0;
}
