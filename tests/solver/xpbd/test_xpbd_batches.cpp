// solver.ordering: batches (solver/xpbd/xpbd_batches): a cloth's stretch
// constraints and bending stencils in NvCloth's simd batches, and the plan
// that sweeps them.
#include <catch2/catch.hpp>

#include <algorithm>
#include <array>
#include <bit>
#include <cstddef>
#include <set>
#include <vector>

#include "common/xpbd_tet.h"
#include "model/cloth_builder.hpp"
#include "scene/scene_loader.hpp"
#include "solver/xpbd/xpbd_batches.hpp"
#include "solver/xpbd/xpbd_plan.hpp"
#include "support/scenes.hpp"

using namespace atssim;
using namespace atssim::solver;
using namespace atssim::solver::xpbd;

namespace {

SimLayout cloth_layout(int resolution) {
  return make_sim_layout(
      model::build_model(scene::parse_scene(test::hanging_cloth_yaml(resolution, 1e4, 1e-3), "s.yaml", ".")));
}

std::vector<int> particles(const ats_distance_c& c) { return {c.a, c.b}; }
std::vector<int> particles(const ats_bend_c& c) { return {c.v[0], c.v[1], c.v[2], c.v[3]}; }
std::vector<int> particles(const ats_tet_c& c) { return {c.v[0], c.v[1], c.v[2], c.v[3]}; }

SimLayout bar_layout(int cells) {
  return make_sim_layout(model::build_model(scene::parse_scene(test::stvk_bar_yaml(cells), "s.yaml", ".")));
}

// Whether two elements are the same bit for bit.
template <class T>
bool same_bytes(const T& a, const T& b) {
  using Bytes = std::array<std::byte, sizeof(T)>;
  return std::bit_cast<Bytes>(a) == std::bit_cast<Bytes>(b);
}

// Every element of `set` exactly once, bit for bit; the dummy's particles past
// the last one; no two real lanes of a batch sharing a particle (with `x`,
// a movable one: lanes that share a pinned particle write it unchanged).
template <class Element>
void check_batches(const std::vector<Element>& set, const ElementBatches<Element>& b, int n,
                   const std::vector<Float4>* x = nullptr) {
  REQUIRE(b.elements.size() == b.source.size());
  REQUIRE(b.elements.size() % kBatchWidth == 0);
  std::vector<int> times(set.size(), 0);
  int conflicting_batches = 0;
  for (int batch = 0; batch < b.batches(); ++batch) {
    std::set<int> seen;
    int used = 0;
    for (int l = 0; l < kBatchWidth; ++l) {
      const std::size_t k = static_cast<std::size_t>(batch) * kBatchWidth + static_cast<std::size_t>(l);
      const int s = b.source[k];
      if (s < 0) {
        CHECK(particles(b.elements[k])[0] >= n);
        continue;
      }
      ++times[static_cast<std::size_t>(s)];
      CHECK(same_bytes(b.elements[k], set[static_cast<std::size_t>(s)]));
      for (int p : particles(b.elements[k])) {
        if (x != nullptr && (*x)[static_cast<std::size_t>(p)].w == 0.0f) continue;
        seen.insert(p);
        ++used;
      }
    }
    conflicting_batches += static_cast<int>(seen.size()) == used ? 0 : 1;
  }
  CHECK(conflicting_batches == 0);
  CHECK(std::count(times.begin(), times.end(), 1) == static_cast<long>(set.size()));
}

}  // namespace

TEST_CASE("batches of a cloth: every constraint and stencil exactly once, every batch conflict-free") {
  const SimLayout layout = cloth_layout(GENERATE(5, 16));
  const int n = static_cast<int>(layout.x.size());
  check_batches(layout.stretch, batch_elements(layout.stretch, n), n);
  check_batches(layout.bend, batch_elements(layout.bend, n), n);
}

TEST_CASE("batches: most batches of a 16 x 16 cloth are full (little padding)") {
  const SimLayout layout = cloth_layout(16);
  const auto b = batch_elements(layout.stretch, static_cast<int>(layout.x.size()));
  const auto dummies = std::count(b.source.begin(), b.source.end(), -1);
  INFO(dummies << " dummies in " << b.source.size() << " slots");
  CHECK(dummies < static_cast<long>(b.source.size() / 10));
}

TEST_CASE("the batches plan: one stretch and one bending sweep per iteration, for one device") {
  const SimLayout layout = cloth_layout(10);
  const int iterations = 3;
  XpbdBuffers ids;
  const auto plan = make_xpbd_plan(layout, {1.0 / 240.0, iterations, XpbdOrdering::batches}, &ids);
  CHECK(plan.tasks_of(solver::xpbd::kStretch).size() == std::size_t(iterations));
  CHECK(plan.tasks_of(solver::xpbd::kBend).size() == std::size_t(iterations));
  CHECK(plan.graph.size() == std::size_t(2 + 2 * iterations));
  for (sched::TaskId t : plan.tasks_of(solver::xpbd::kStretch)) {
    REQUIRE(plan.launches[t].size() == 1);
    CHECK(plan.launches[t][0].function == "xpbd_stretch_batches");
    CHECK(plan.launches[t][0].range.count == 1);  // one work-item sweeps the set
  }
  const auto padded = batch_elements(layout.stretch, static_cast<int>(layout.x.size()));
  CHECK(plan.buffers[ids.stretch].initial.size() == padded.elements.size() * sizeof(ats_distance_c));
  CHECK_FALSE(plan.one_device_reason.empty());
  CHECK(make_xpbd_plan(layout, {1.0 / 240.0, iterations}).one_device_reason.empty());
}

// solver.ordering: color_batches: each color block cut into batches, the
// blocks' boundaries on whole batches, every batch's elements from its block.
template <class Element>
void check_color_batches(const std::vector<Element>& set, const std::vector<int>& blocks,
                         const ColorBatches<Element>& cb, const std::vector<Float4>& x) {
  const int n = static_cast<int>(x.size());
  check_batches(set, cb.set, n, &x);
  REQUIRE(cb.blocks.size() == blocks.size());
  CHECK(cb.blocks.front() == 0);
  CHECK(cb.blocks.back() == cb.set.batches());
  for (std::size_t b = 0; b + 1 < blocks.size(); ++b) {
    const int count = blocks[b + 1] - blocks[b];
    // As few batches as the block's elements need: at most 7 dummies a block.
    CHECK(cb.blocks[b + 1] - cb.blocks[b] == (count + kBatchWidth - 1) / kBatchWidth);
    for (int k = cb.blocks[b] * kBatchWidth; k < cb.blocks[b + 1] * kBatchWidth; ++k) {
      const int s = cb.set.source[static_cast<std::size_t>(k)];
      if (s >= 0) CHECK((s >= blocks[b] && s < blocks[b + 1]));
    }
  }
}

TEST_CASE("color batches of a cloth: every element once, in its color block, every batch conflict-free") {
  const SimLayout layout = cloth_layout(GENERATE(5, 16));
  const int n = static_cast<int>(layout.x.size());
  check_color_batches(layout.stretch, layout.stretch_blocks, color_batches(layout.stretch, layout.stretch_blocks, n),
                      layout.x);
  check_color_batches(layout.bend, layout.bend_blocks, color_batches(layout.bend, layout.bend_blocks, n), layout.x);
}

TEST_CASE("the color_batches plan: one task per color block and iteration, a work-item per batch, any schedule") {
  const SimLayout layout = cloth_layout(10);
  const int n = static_cast<int>(layout.x.size());
  const int iterations = 3;
  XpbdBuffers ids;
  const auto plan = make_xpbd_plan(layout, {1.0 / 240.0, iterations, XpbdOrdering::color_batches}, &ids);
  const auto stretch = color_batches(layout.stretch, layout.stretch_blocks, n);
  const auto stretch_tasks = plan.tasks_of(solver::xpbd::kStretch);
  REQUIRE(stretch_tasks.size() == (layout.stretch_blocks.size() - 1) * std::size_t(iterations));
  CHECK(plan.tasks_of(solver::xpbd::kBend).size() == (layout.bend_blocks.size() - 1) * std::size_t(iterations));
  for (std::size_t k = 0; k < stretch_tasks.size(); ++k) {
    const auto& launch = plan.launches[stretch_tasks[k]].at(0);
    const std::size_t b = k % (layout.stretch_blocks.size() - 1);
    CHECK(launch.function == "xpbd_stretch_lanes");
    CHECK(launch.range.first == stretch.blocks[b]);
    CHECK(launch.range.count == stretch.blocks[b + 1] - stretch.blocks[b]);
    // A batch writes its 8 elements' particles (16) and multipliers (8 floats).
    CHECK(launch.writes.at(0).arity == 2 * kBatchWidth);
    CHECK(launch.writes.at(1).element_bytes == kBatchWidth * sizeof(float));
  }
  CHECK(plan.buffers[ids.stretch].initial.size() == stretch.set.elements.size() * sizeof(ats_distance_c));
  CHECK(plan.one_device_reason.empty());
}

TEST_CASE("batches and color batches of a solid's tets: every tet once, every batch conflict-free") {
  const SimLayout layout = bar_layout(GENERATE(1, 3));
  const int n = static_cast<int>(layout.x.size());
  REQUIRE(layout.tets.size() >= 24);
  check_batches(layout.tets, batch_elements(layout.tets, n), n);
  check_color_batches(layout.tets, layout.tet_blocks, color_batches(layout.tets, layout.tet_blocks, n), layout.x);
}

TEST_CASE("the tet tasks under each ordering: color blocks, blocks of batches, one sweep") {
  const SimLayout layout = bar_layout(2);
  const int n = static_cast<int>(layout.x.size());
  const int iterations = 2;
  const std::size_t blocks = layout.tet_blocks.size() - 1;
  for (const XpbdOrdering ordering : {XpbdOrdering::colors, XpbdOrdering::color_batches, XpbdOrdering::batches}) {
    XpbdBuffers ids;
    const auto plan = make_xpbd_plan(layout, {1.0 / 240.0, iterations, ordering}, &ids);
    const auto tasks = plan.tasks_of(solver::xpbd::kTet);
    const auto lanes = color_batches(layout.tets, layout.tet_blocks, n);
    const auto sweep = batch_elements(layout.tets, n);
    if (ordering == XpbdOrdering::batches) {
      REQUIRE(tasks.size() == std::size_t(iterations));
      CHECK(plan.launches[tasks[0]].at(0).function == "xpbd_tet_batches");
      CHECK(plan.buffers[ids.tet].initial.size() == sweep.elements.size() * sizeof(ats_tet_c));
      continue;
    }
    REQUIRE(tasks.size() == blocks * std::size_t(iterations));
    const bool batched = ordering == XpbdOrdering::color_batches;
    int items = 0;
    for (std::size_t k = 0; k < blocks; ++k) {
      const auto& launch = plan.launches[tasks[k]].at(0);
      CHECK(launch.function == (batched ? "xpbd_tet_lanes" : "xpbd_tet"));
      CHECK(launch.range.first == (batched ? lanes.blocks[k] : layout.tet_blocks[k]));
      items += launch.range.count;
      // A batch writes its 8 tets' particles (32) and multipliers (8 × 8 floats).
      CHECK(launch.writes.at(0).arity == (batched ? 4 * kBatchWidth : 4));
      CHECK(launch.writes.at(1).element_bytes == (batched ? kBatchWidth : 1) * ATS_TET_LAMBDA_STRIDE * sizeof(float));
    }
    CHECK(items == (batched ? lanes.set.batches() : static_cast<int>(layout.tets.size())));
    CHECK(plan.buffers[ids.tet_lambda].initial.size() ==
          (batched ? lanes.set.elements.size() : layout.tets.size()) * ATS_TET_LAMBDA_STRIDE * sizeof(float));
  }
}
