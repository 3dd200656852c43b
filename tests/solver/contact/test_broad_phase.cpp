// The two broad phases of bench/bench_broad_phase (the device's refitted BVH
// mirrored on the host, and a spatial hash rebuilt per step) against a brute
// force over every pair, on a folded, crumpled sheet whose layers come within
// the query radius.
#include <catch2/catch.hpp>

#include <random>

#include "broad_phase/bvh_pairs.hpp"
#include "broad_phase/crumpled_sheet.hpp"
#include "broad_phase/hash_pairs.hpp"

using namespace atssim;
using namespace atssim::bench;

namespace {

struct Found {
  PairLists brute, bvh, hash;
};

Found find_all(const solver::SelfContactLayout& s, const std::vector<ats_vec3>& x, float cell) {
  const float r = s.query_radius;
  Found f;
  brute_force_pairs(s, x, r, 0, static_cast<int>(std::max(x.size(), s.edges.size())), f.brute);
  std::vector<Float4> nodes;
  bvh_refit(s, x, nodes);
  bvh_query(s, x, nodes, r, f.bvh);
  SurfaceHash h;
  hash_resize(h, s, static_cast<int>(x.size()), cell);
  hash_build(h, s, x);
  hash_query(s, x, h, r, f.hash);
  f.brute.sort();
  f.bvh.sort();
  f.hash.sort();
  return f;
}

}  // namespace

TEST_CASE("the BVH walk and the spatial hash find exactly the brute force's pairs on a crumpled sheet",
          "[solver][contact][broad_phase]") {
  const int n = GENERATE(16, 24, 40);
  const float cell_factor = GENERATE(1.0f, 2.0f, 4.0f);
  const model::Model m = crumpled_sheet(n);
  const solver::SelfContactLayout s = solver::make_self_contact_layout(m);
  const std::vector<ats_vec3> x = float_positions(m.particles.position);
  const Found f = find_all(s, x, cell_factor * s.query_radius);
  CAPTURE(n, cell_factor, f.brute.vt.size(), f.brute.ee.size());
  REQUIRE(f.brute.vt.size() > 0);
  REQUIRE(f.brute.ee.size() > 0);
  CHECK(transposes_agree(f.brute));
  CHECK(same_pairs(f.bvh, f.brute));
  CHECK(same_pairs(f.hash, f.brute));
}

TEST_CASE("the BVH built on one state and refitted on a moved one still finds every pair",
          "[solver][contact][broad_phase]") {
  const model::Model m = crumpled_sheet(24);
  const solver::SelfContactLayout s = solver::make_self_contact_layout(m);
  std::vector<ats_vec3> x = float_positions(m.particles.position);
  std::mt19937 rng(12);
  std::normal_distribution<float> jitter(0.0f, 0.5f * s.query_radius);
  for (auto& p : x) p = ats_v3(p.x + jitter(rng), p.y + jitter(rng), p.z + jitter(rng));
  const Found f = find_all(s, x, 2.0f * s.query_radius);
  REQUIRE(f.brute.found() > 0);
  CHECK(same_pairs(f.bvh, f.brute));
  CHECK(same_pairs(f.hash, f.brute));
}

TEST_CASE("the spatial hash finds each pair once when many cells share a bucket", "[solver][contact][broad_phase]") {
  const model::Model m = crumpled_sheet(24);
  const solver::SelfContactLayout s = solver::make_self_contact_layout(m);
  const std::vector<ats_vec3> x = float_positions(m.particles.position);
  const float r = s.query_radius;
  PairLists brute, hash;
  brute_force_pairs(s, x, r, 0, static_cast<int>(s.edges.size()), brute);
  SurfaceHash h;
  hash_resize(h, s, static_cast<int>(x.size()), r);
  h.vertices.table = h.triangles.table = h.edges.table = 7;  // collisions in every bucket
  hash_build(h, s, x);
  hash_query(s, x, h, r, hash);
  brute.sort();
  hash.sort();
  CHECK(same_pairs(hash, brute));
}

TEST_CASE("the query radius follows the substep's largest predicted step, between 1.5 thicknesses and the cap",
          "[solver][contact][broad_phase]") {
  // R = max(1.5 r, r + 2.5 delta, 5 delta), at most r_max; r = 1 mm, r_max = 3 mm.
  const float r = 0.001f, cap = 0.003f;
  const auto radius = [&](std::vector<float> blocks) {
    return sc_motion_radius(blocks.data(), static_cast<int>(blocks.size()), r, cap);
  };
  CHECK(radius({0.0f, 0.0f}) == Approx(0.0015));         // at rest: the floor
  CHECK(radius({0.0001f, 0.0003f}) == Approx(0.00175));  // r + 2.5 delta (delta 0.3 mm, the larger block)
  CHECK(radius({0.0005f}) == Approx(0.0025));            // 5 delta beats r + 2.5 delta past 0.4 r
  CHECK(radius({0.002f, 0.0f}) == Approx(0.003));        // the cap
  // the block's largest step counts surface vertices only
  const std::vector<Float4> start{{0, 0, 0, 1}, {0, 0, 0, 1}, {0, 0, 0, 1}};
  const std::vector<Float4> guess{{0.0003f, 0, 0, 1}, {0, 0.0004f, 0, 1}, {0, 0, 0.9f, 1}};
  const std::vector<int> inc{0, 1, 2, 2};  // particle 2 has no triangle (first n + 1 offsets)
  CHECK(sc_block_motion(0, start.data(), guess.data(), inc.data(), 3) == Approx(0.0004));
}
