// The two broad phases of bench/bench_broad_phase (the device's refitted BVH
// mirrored on the host, and a spatial hash rebuilt per step) against a brute
// force over every pair, on a folded, crumpled sheet whose layers come within
// the query radius.
#include <catch2/catch.hpp>

#include <cmath>
#include <random>

#include "broad_phase/bvh_pairs.hpp"
#include "broad_phase/crumpled_sheet.hpp"
#include "broad_phase/hash_pairs.hpp"
#include "common/self_contact_lists.h"  // after bvh_pairs.hpp, which defines ats_float4

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
  REQUIRE(!f.brute.vt.empty());
  REQUIRE(!f.brute.ee.empty());
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

TEST_CASE("the radius a substep needs follows its largest predicted step, between 1.5 thicknesses and the cap",
          "[solver][contact][broad_phase]") {
  // max(1.5 r, r + 2.5 delta, 5 delta), at most r_max; r = 1 mm, r_max = 3 mm.
  const float r = 0.001f, cap = 0.003f;
  CHECK(sc_needed_radius(0.0f, r, cap) == Approx(0.0015));      // at rest: the floor
  CHECK(sc_needed_radius(0.0003f, r, cap) == Approx(0.00175));  // r + 2.5 delta
  CHECK(sc_needed_radius(0.0005f, r, cap) == Approx(0.0025));   // 5 delta beats r + 2.5 delta past 0.4 r
  CHECK(sc_needed_radius(0.002f, r, cap) == Approx(0.003));     // the cap
}

TEST_CASE("the gap and the longest distance between two boxes", "[solver][contact][broad_phase]") {
  const auto box = [](ats_vec3 lo, ats_vec3 hi) {
    sc_box b;
    b.lo = lo;
    b.hi = hi;
    return b;
  };
  const sc_box a = box(ats_v3(0, 0, 0), ats_v3(1, 1, 1));
  CHECK(sc_boxes_gap(a, box(ats_v3(0.5f, 0.5f, 0.5f), ats_v3(2, 2, 2))) == 0.0f);  // overlapping
  CHECK(sc_boxes_gap(a, box(ats_v3(4, 5, 0), ats_v3(6, 6, 1))) == Approx(5.0));    // (3, 4, 0) apart
  CHECK(sc_boxes_gap(box(ats_v3(4, 5, 0), ats_v3(6, 6, 1)), a) == Approx(5.0));
  // the farthest corners: (0, 0, 0) and (6, 6, 1)
  CHECK(sc_boxes_most_apart(a, box(ats_v3(4, 5, 0), ats_v3(6, 6, 1))) == Approx(std::sqrt(73.0)));
  CHECK(sc_boxes_most_apart(a, a) == Approx(std::sqrt(3.0)));  // a box against itself: its diagonal
  const sc_box p = box(ats_v3(1, 2, 3), ats_v3(1, 2, 3));
  CHECK(sc_boxes_most_apart(p, p) == 0.0f);  // one point: every vertex moved alike
}

TEST_CASE("a block's motion is the box of its triangles' corners, their displacements and their steps",
          "[solver][contact][broad_phase]") {
  // Two triangles in a block (leaves 0 and 1) over four vertices; vertex 4
  // belongs to no triangle and moves far.
  const std::vector<Float4> prev{{0, 0, 0, 1}, {1, 0, 0, 1}, {0, 1, 0, 1}, {1, 1, 0, 1}, {5, 5, 5, 1}};
  std::vector<Float4> start = prev, guess;
  start[1].x += 0.0003f;  // moved since the substep before: (0.3, 0, 0) mm
  start[3].y -= 0.0001f;  // (0, -0.1, 0) mm
  start[4].z += 0.9f;
  guess = start;
  guess[2].z += 0.0004f;  // the predicted steps: (0, 0, 0.4) mm
  // The block's corners, each once: triangles (0, 1, 2) and (1, 3, 2).
  const std::vector<int> corner_start{0, 4}, corners{0, 1, 2, 3};
  std::vector<float> out(ATS_SC_BLOCK_FLOATS);
  sc_block_motion(0, prev.data(), start.data(), guess.data(), corner_start.data(), corners.data(), out.data());
  CHECK(out[0] == 0.0f);  // x_t: [0, 1.0003] x [0, 1] x [0, 0]
  CHECK(out[3] == Approx(1.0003));
  CHECK(out[4] == Approx(1.0));
  CHECK((out[2] == 0.0f && out[5] == 0.0f));     // vertex 4's 0.9 m is in no box
  CHECK(out[6] == 0.0f);                         // displacements: [0, 0.3] x [-0.1, 0] x 0 mm
  CHECK(out[9] == Approx(0.0003).margin(1e-7));  // (1.0003 - 1 in float)
  CHECK(out[7] == Approx(-0.0001).margin(1e-7));
  CHECK((out[10] == 0.0f && out[8] == 0.0f && out[11] == 0.0f));
  CHECK((out[12] == 0.0f && out[13] == 0.0f && out[14] == 0.0f && out[15] == 0.0f && out[16] == 0.0f));
  CHECK(out[17] == Approx(0.0004));  // steps: 0 to 0.4 mm in z
}

namespace {
// Block motion records (sc_block_motion's layout) from the boxes of x_t, of
// the displacements and of the steps.
struct BlockMotion {
  ats_vec3 lo, hi, moved_lo, moved_hi, step_lo, step_hi;
};
std::vector<float> motion_of(const std::vector<BlockMotion>& blocks) {
  std::vector<float> out;
  for (const BlockMotion& b : blocks)
    for (const ats_vec3& v : {b.lo, b.hi, b.moved_lo, b.moved_hi, b.step_lo, b.step_hi})
      out.insert(out.end(), {v.x, v.y, v.z});
  return out;
}
}  // namespace

TEST_CASE(
    "a block keeps its lists while its motion against the blocks near it leaves them the radius the substep needs, "
    "and only it remakes them",
    "[solver][contact][broad_phase]") {
  // r = 1 mm, R_det = 3 mm; at rest the substep needs R = 1.5 mm. Blocks A
  // and B are 1 mm apart, C is 1 m away. The motions are since x_det, which
  // moves to x_t when some block makes its lists.
  const float r = 0.001f, cap = 0.003f;
  const ats_vec3 o = ats_v3(0, 0, 0);
  std::vector<int> state(ATS_SC_STATE_INTS, 0);
  std::vector<float> rho0(3, 0.0f), rho(3, 0.0f);  // as a run starts: no lists
  std::vector<int> make(3, 0);
  const auto decide = [&](const std::vector<BlockMotion>& blocks) {
    const std::vector<float> m = motion_of(blocks);
    const int n = static_cast<int>(blocks.size());
    std::vector<float> clusters(6);
    sc_cluster_box(0, m.data(), n, clusters.data());
    for (int b = 0; b < n; ++b)
      sc_block_decide(b, m.data(), clusters.data(), n, r, cap, rho0.data(), rho.data(), make.data());
    sc_decide_any(make.data(), n, cap, rho.data(), rho0.data(), state.data());
    return make;
  };
  const BlockMotion a{o, ats_v3(0.1f, 0.1f, 0), o, o, o, o};
  const BlockMotion b{ats_v3(0.101f, 0, 0), ats_v3(0.2f, 0.1f, 0), o, o, o, o};
  const BlockMotion c{ats_v3(1.2f, 0, 0), ats_v3(1.3f, 0.1f, 0), o, o, o, o};
  CHECK(decide({a, b, c}) == std::vector<int>{1, 1, 1});  // the first substep makes every block's lists
  CHECK(state[1] == 1);
  CHECK(sc_bits_float(state[2]) == cap);
  CHECK(rho == std::vector<float>{cap, cap, cap});
  CHECK(rho0 == rho);
  // B moved 0.8 mm towards A, every vertex alike: A and B each lose 0.8 mm
  // (A's erosion against B, B's against A), C, 1 m away, nothing.
  BlockMotion b2 = b;
  b2.moved_lo = b2.moved_hi = ats_v3(-0.0008f, 0, 0);
  CHECK(decide({a, b2, c}) == std::vector<int>{0, 0, 0});
  CHECK(state[1] == 0);
  CHECK(rho[0] == Approx(0.0022).epsilon(1e-3));
  CHECK(rho[1] == Approx(0.0022).epsilon(1e-3));
  CHECK(rho[2] == cap);
  CHECK(rho0 == std::vector<float>{cap, cap, cap});  // no block made lists: x_det stays
  // B back where it was: measured since x_det, the motion there and back
  // does not add up.
  CHECK(decide({a, b, c}) == std::vector<int>{0, 0, 0});
  CHECK(rho == std::vector<float>{cap, cap, cap});
  // B at 0.8 mm again, and C turns (its corners spread 1 cm): only C's lists
  // go and are remade; A and B, far from it, are kept, and their rho at the
  // new x_det is 2.2 mm.
  BlockMotion c2 = c;
  c2.moved_hi = ats_v3(0.01f, 0, 0);
  CHECK(decide({a, b2, c2}) == std::vector<int>{0, 0, 1});
  CHECK(state[1] == 1);
  CHECK(rho[2] == cap);
  CHECK(rho0[0] == Approx(0.0022).epsilon(1e-3));
  CHECK(rho0[1] == Approx(0.0022).epsilon(1e-3));
  CHECK(rho0[2] == cap);
  // Everything moves 2 cm down, with the same steps: no relative motion, kept.
  const ats_vec3 down = ats_v3(0, -0.02f, 0);
  std::vector<BlockMotion> falling{a, b, c};
  for (BlockMotion& m : falling) m.moved_lo = m.moved_hi = m.step_lo = m.step_hi = down;
  CHECK(decide(falling) == std::vector<int>{0, 0, 0});
  CHECK(rho == rho0);
  // B closes on A by another 0.8 mm since: 2.2 - 0.8 = 1.4 mm < 1.5 mm,
  // both remake; C is kept.
  CHECK(decide({a, b2, c}) == std::vector<int>{1, 1, 0});
  CHECK(rho == std::vector<float>{cap, cap, cap});
  // A's steps spread over 1.2 mm (delta 0.6 mm): A and B, which is near
  // it, need 5 delta = 3 mm, the whole of R_det, so any motion at all
  // remakes their lists; C, far from A, needs 1.5 mm still and keeps its.
  BlockMotion a3 = a;
  a3.step_lo = ats_v3(0, -0.0012f, 0);
  a3.moved_hi = ats_v3(1e-6f, 0, 0);
  CHECK(decide({a3, b, c}) == std::vector<int>{1, 1, 0});
  // Now C's steps spread over 1.2 mm and it moved 1 um, while B closed on A
  // by 0.8 mm: C needs 3 mm and remakes, A and B need 1.5 mm still (C is far
  // from them) and keep theirs at 2.2 mm. With the whole surface's fastest
  // step deciding for all, they would have remade theirs too.
  BlockMotion c3 = c;
  c3.step_lo = ats_v3(0, -0.0012f, 0);
  c3.moved_hi = ats_v3(1e-6f, 0, 0);
  CHECK(decide({a, b2, c3}) == std::vector<int>{0, 0, 1});
  CHECK(rho0[0] == Approx(0.0022).epsilon(1e-3));
  CHECK(state[4] == 5);  // substeps that made lists
  CHECK(state[5] == 9);  // blocks' lists made: 3 + 1 + 2 + 2 + 1
}

TEST_CASE(
    "the decision passed over clusters of blocks far away is the decision of every block against every block, bit "
    "for bit",
    "[solver][contact][broad_phase]") {
  // 200 blocks (7 clusters, the last short) scattered over a 0.3 m cube in
  // patches, with random displacements of up to 0.3 mm and steps; against a
  // plain loop over every pair of blocks, written here after
  // self_contact_lists.h's rule (rho = rho0 - 1.001 e over the blocks whose
  // x_t box is within 1.001 rho0; make where rho < the radius needed).
  const int n = 200;
  const float r = 0.001f, cap = 0.003f;
  std::mt19937 rng(11);
  std::uniform_real_distribution<float> where(0.0f, 0.3f), size(0.0f, 0.02f), move(-0.0003f, 0.0003f);
  std::vector<BlockMotion> blocks(n);
  for (BlockMotion& m : blocks) {
    m.lo = ats_v3(where(rng), where(rng), where(rng));
    m.hi = ats_add(m.lo, ats_v3(size(rng), size(rng), size(rng)));
    m.moved_lo = ats_v3(move(rng), move(rng), move(rng));
    m.moved_hi = ats_add(m.moved_lo, ats_v3(0.01f * size(rng), 0.01f * size(rng), 0.01f * size(rng)));
    m.step_lo = ats_scale(m.moved_lo, 0.1f);
    m.step_hi = ats_scale(m.moved_hi, 0.1f);
  }
  const std::vector<float> m = motion_of(blocks);
  std::vector<float> clusters(6 * ((n + ATS_SC_CLUSTER - 1) / ATS_SC_CLUSTER));
  for (int k = 0; k * ATS_SC_CLUSTER < n; ++k) sc_cluster_box(k, m.data(), n, clusters.data());
  // Cluster 6 holds blocks 192..199: its box is theirs.
  float lo_x = 1e30f;
  for (int c = 192; c < n; ++c) lo_x = std::min(lo_x, m[ATS_SC_BLOCK_FLOATS * c]);
  CHECK(clusters[36] == lo_x);
  std::vector<float> rho0(n), rho(n);
  std::vector<int> make(n);
  for (int b = 0; b < n; ++b) rho0[b] = b % 10 == 0 ? 0.0f : cap * (0.5f + 0.5f * float(b % 7) / 6.0f);
  for (int b = 0; b < n; ++b)
    sc_block_decide(b, m.data(), clusters.data(), n, r, cap, rho0.data(), rho.data(), make.data());
  int kept = 0, skipped_some = 0;
  for (int a = 0; a < n; ++a) {
    const BlockMotion& A = blocks[a];
    const sc_box at{A.lo, A.hi}, moved{A.moved_lo, A.moved_hi}, step{A.step_lo, A.step_hi};
    bool want_make = !(rho0[a] > 0.0f);
    float want_rho = cap;
    if (!want_make) {
      float e = 0.0f, spread = 0.0f;
      int near = 0;
      for (int c = 0; c < n; ++c) {
        const BlockMotion& C = blocks[c];
        if (!(sc_boxes_gap(at, sc_box{C.lo, C.hi}) <= 1.001f * rho0[a])) continue;
        ++near;
        e = std::max(e, sc_boxes_most_apart(moved, sc_box{C.moved_lo, C.moved_hi}));
        spread = std::max(spread, sc_boxes_most_apart(step, sc_box{C.step_lo, C.step_hi}));
      }
      skipped_some += near < n;
      const float now = rho0[a] - 1.001f * e;
      want_make = !(now >= sc_needed_radius(0.5f * spread, r, cap));
      if (!want_make) want_rho = now;
    }
    CHECK(make[a] == int(want_make));
    CHECK(rho[a] == want_rho);
    kept += !want_make;
  }
  // Both outcomes occur, and blocks far apart are passed over.
  CHECK(kept > 10);
  CHECK(kept < n - 10);
  CHECK(skipped_some > 100);
}
