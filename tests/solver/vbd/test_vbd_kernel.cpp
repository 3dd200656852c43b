#include <catch2/catch.hpp>

#include <cmath>

#include "model/cloth_builder.hpp"
#include "scene/scene_loader.hpp"
#include "solver/vbd/vbd_plan.hpp"
#include "solver/vbd/vbd_reference.hpp"
#include "solver/vertex_starts.hpp"
#include "support/positions.hpp"

using namespace atssim;
using namespace atssim::solver;

namespace {

constexpr double kH = 1.0 / 240.0;
constexpr int kIterations = 8;
constexpr int kSubsteps = 4;

// x and v after kSubsteps of the plan on the whole CPU device.
std::pair<std::vector<Float4>, std::vector<Float4>> run_plan(const SimLayout& start, vbd::VbdOrdering ordering) {
  vertex::VertexBuffers ids;
  const auto plan = vbd::make_vbd_plan(start, kH, kIterations, &ids, ordering);
  return test::run_on_cpu(plan, ids, kSubsteps);
}

}  // namespace

TEST_CASE("the OpenCL VBD plan and the host VBD reference agree to 1e-5 after a few substeps", "[vbd]") {
  const std::string scene = GENERATE("cloth", "cloth over the ground", "neo-Hookean solid");
  const bool lanes = GENERATE(false, true);  // solver.ordering colors or color_batches, on both sides
  INFO(scene << (lanes ? ", color_batches" : ", colors"));
  const SimLayout start = test::vertex_start(scene, kH);
  const auto [device_x, device_v] = run_plan(start, lanes ? vbd::VbdOrdering::color_batches : vbd::VbdOrdering::colors);

  vbd::VbdReference ref(start, kH, kIterations, 1, lanes);
  for (int s = 0; s < kSubsteps; ++s) ref.substep();
  REQUIRE(device_x.size() == ref.state().x.size());
  const double dx = test::max_distance(device_x, ref.state().x);
  const double dv = test::max_distance(device_v, ref.state().v);
  const double moved = test::max_distance(ref.state().x, start.x);
  INFO(scene << ": max |dx| " << dx << " max |dv| " << dv << " moved " << moved);
  CHECK(moved > 1e-4);  // the substeps really changed the state
  CHECK(dx < 1e-5);
  CHECK(dv < 1e-5 / kH);
}

TEST_CASE("the VBD kernel's lanes (color_batches) give the colors' bits", "[vbd]") {
  // The lanes' gather is the scalar one's operations per lane
  // (common/vertex_system_lanes.h): springs and isometric stencils as
  // vectors, dihedral stencils and tets lane by lane.
  const std::string scene =
      GENERATE("cloth over the ground", "cloth, half dihedral, damped springs", "neo-Hookean solid");
  INFO(scene);
  const SimLayout start = test::vertex_start(scene, kH);
  const auto colors = run_plan(start, vbd::VbdOrdering::colors);
  const auto lanes = run_plan(start, vbd::VbdOrdering::color_batches);
  CHECK(test::max_distance(colors.first, start.x) > 1e-4);  // it moved
  CHECK(test::same_bits(colors, lanes));
}
