// The two broad phases of bench/bench_broad_phase (the device's refitted BVH
// mirrored on the host, and a spatial hash rebuilt per step) against a brute
// force over every pair, on a folded, crumpled sheet whose layers come within
// the query radius.
#include <catch2/catch.hpp>

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

// One motion block (common/self_contact_lists.h sc_block_motion): the box of the
// displacements since the lists were made, then the box of the predicted steps.
namespace {
std::vector<float> block(ats_vec3 moved_lo, ats_vec3 moved_hi, ats_vec3 step_lo, ats_vec3 step_hi) {
  return {moved_lo.x, moved_lo.y, moved_lo.z, moved_hi.x, moved_hi.y, moved_hi.z,
          step_lo.x,  step_lo.y,  step_lo.z,  step_hi.x,  step_hi.y,  step_hi.z};
}
}  // namespace

TEST_CASE(
    "the lists are made at the start and when the relative motion since outgrows them, else kept or remade as they "
    "were",
    "[solver][contact][broad_phase]") {
  const float r = 0.001f, cap = 0.003f;
  const ats_vec3 o = ats_v3(0, 0, 0);
  std::vector<int> state(ATS_SC_STATE_INTS, 0);  // as a run starts
  int in_memory = 0;
  const auto decide = [&](const std::vector<float>& blocks) {
    sc_decide(blocks.data(), static_cast<int>(blocks.size() / ATS_SC_MOTION_FLOATS), r, cap, state.data(), &in_memory);
    CHECK(state[1] == state[5]);  // (the lists stay in memory here: made anew or kept)
    return state[1];
  };
  CHECK(decide(block(o, o, o, o)) == 1);  // a frame's first substep detects, at the cap
  CHECK(sc_bits_float(state[2]) == Approx(cap));
  // kept while need + 2 D <= 3 mm: need 1.5 mm (at rest), D (half the box's
  // diagonal) up to 0.75 mm
  CHECK(decide(block(o, ats_v3(0.0014f, 0, 0), o, o)) == 0);
  CHECK(sc_bits_float(state[3]) == Approx(0.0007));           // D
  CHECK(decide(block(o, ats_v3(0.0016f, 0, 0), o, o)) == 1);  // 1.5 + 1.6 mm > 3 mm
  CHECK(sc_bits_float(state[3]) == 0.0f);                     // made here
  // Two blocks: their boxes join (D = half of |(1.2, 0.9, 0) mm| = 0.75 mm).
  std::vector<float> two = block(o, ats_v3(0.0012f, 0, 0), o, o);
  const std::vector<float> other = block(ats_v3(0, 0.0009f, 0), ats_v3(0, 0.0009f, 0), o, o);
  two.insert(two.end(), other.begin(), other.end());
  CHECK(decide(two) == 0);
  CHECK(sc_bits_float(state[3]) == Approx(0.00075));
  // Everything moved 1 m and steps 2 cm down: no relative motion, kept.
  const ats_vec3 far = ats_v3(1, 0, 0), down = ats_v3(0, -0.02f, 0);
  CHECK(decide(block(far, far, down, down)) == 0);
  CHECK(sc_bits_float(state[3]) == 0.0f);
  // Steps spread over 0.6 mm: delta 0.3 mm, need r + 2.5 delta = 1.75 mm.
  CHECK(decide(block(o, ats_v3(0.0002f, 0, 0), ats_v3(0, -0.0006f, 0), o)) == 0);  // 1.75 + 0.2 mm
  CHECK(decide(block(o, ats_v3(0.0002f, 0, 0), ats_v3(0, -0.0012f, 0), o)) == 1);  // need 3 mm (5 delta)
  CHECK(state[4] == 3);                                                            // made anew three times
  // A reset clears in_memory: the lists kept are made again where they were
  // made (state[1], not state[5]), and the decision is the same.
  in_memory = 0;
  sc_decide(block(o, ats_v3(0.0002f, 0, 0), ats_v3(0, -0.0006f, 0), o).data(), 1, r, cap, state.data(), &in_memory);
  CHECK(state[1] == 1);
  CHECK(state[5] == 0);
  CHECK(sc_bits_float(state[3]) == Approx(0.0001));  // D still since x_det
  CHECK(state[4] == 3);
  CHECK(in_memory == 1);
}

TEST_CASE("a block's motion is the box of its surface vertices' displacements and steps",
          "[solver][contact][broad_phase]") {
  const std::vector<Float4> det{{0, 0, 0, 1}, {0, 0, 0, 1}, {0, 0, 0, 1}};
  const std::vector<Float4> start{{0.0003f, 0, 0, 1}, {0, 0.0001f, 0, 1}, {0, 0, 0.9f, 1}};
  const std::vector<Float4> guess{{0.0003f, 0, 0, 1}, {0, 0.0005f, 0, 1}, {0, 0, 0.0f, 1}};
  const std::vector<int> inc{0, 1, 2, 2};  // particle 2 has no triangle (the first n + 1 offsets)
  std::vector<float> out(ATS_SC_MOTION_FLOATS);
  sc_block_motion(0, det.data(), start.data(), guess.data(), inc.data(), 3, out.data());
  // since the lists were made: (0.3, 0, 0) and (0, 0.1, 0) mm
  CHECK(out[0] == 0.0f);
  CHECK(out[3] == Approx(0.0003));
  CHECK(out[4] == Approx(0.0001));
  CHECK((out[2] == 0.0f && out[5] == 0.0f));  // particle 2's 0.9 m is not a surface's
  // the predicted steps: (0, 0, 0) and (0, 0.4, 0) mm
  CHECK((out[6] == 0.0f && out[7] == 0.0f && out[9] == 0.0f));
  CHECK(out[10] == Approx(0.0004));
  CHECK((out[8] == 0.0f && out[11] == 0.0f));
}
