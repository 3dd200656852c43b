// solver.ordering: batches (solver/xpbd/xpbd_batches): a cloth's stretch
// constraints and bending stencils in NvCloth's simd batches, and the plan
// that sweeps them.
#include <catch2/catch.hpp>

#include <algorithm>
#include <cstring>
#include <set>
#include <vector>

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

// Every element of `set` exactly once, bit for bit; the dummy's particles past
// the last one; no two real lanes of a batch sharing a particle.
template <class Element>
void check_batches(const std::vector<Element>& set, const ElementBatches<Element>& b, int n) {
  REQUIRE(b.elements.size() == b.source.size());
  REQUIRE(b.elements.size() % kBatchWidth == 0);
  std::vector<int> times(set.size(), 0);
  int conflicting_batches = 0;
  for (int batch = 0; batch < b.batches(); ++batch) {
    std::set<int> seen;
    int used = 0;
    for (int l = 0; l < kBatchWidth; ++l) {
      const std::size_t k = static_cast<std::size_t>(batch * kBatchWidth + l);
      const int s = b.source[k];
      if (s < 0) {
        CHECK(particles(b.elements[k])[0] >= n);
        continue;
      }
      ++times[static_cast<std::size_t>(s)];
      CHECK(std::memcmp(&b.elements[k], &set[static_cast<std::size_t>(s)], sizeof(Element)) == 0);
      for (int p : particles(b.elements[k])) seen.insert(p);
      used += static_cast<int>(particles(b.elements[k]).size());
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
