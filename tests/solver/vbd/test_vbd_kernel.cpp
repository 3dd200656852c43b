#include <catch2/catch.hpp>

#include <cmath>
#include <cstring>

#include "device/device_set.hpp"
#include "device/plan_executor.hpp"
#include "model/cloth_builder.hpp"
#include "scene/scene_loader.hpp"
#include "solver/energy/moving_cloth.hpp"
#include "solver/vbd/vbd_plan.hpp"
#include "solver/vbd/vbd_reference.hpp"
#include "support/positions.hpp"

using namespace atssim;
using namespace atssim::solver;

namespace {

constexpr double kH = 1.0 / 240.0;
constexpr int kIterations = 8;
constexpr int kSubsteps = 4;

std::vector<Float4> as_float4(const std::vector<std::byte>& raw) {
  std::vector<Float4> out(raw.size() / sizeof(Float4));
  std::memcpy(out.data(), raw.data(), raw.size());
  return out;
}

// A 0.1 x 0.4 x 0.1 m stable neo-Hookean bar pinned at its top face, moving.
SimLayout moving_soft_box() {
  const std::string yaml =
      "objects:\n"
      "  - type: solid\n"
      "    box: {size: [0.1, 0.4, 0.1], resolution: [2, 8, 2]}\n"
      "    material: {density: 1000, youngs_modulus: 1.0e6, poisson_ratio: 0.3}\n"
      "    pins: {boxes: [{min: [-1, 0.19, -1], max: [1, 0.21, 1]}]}\n";
  SimLayout layout = make_sim_layout(model::build_model(scene::parse_scene(yaml, "s.yaml", ".")));
  for (std::size_t i = 0; i < layout.v.size(); ++i) {
    const float t = static_cast<float>(i);
    layout.v[i] = {0.3f * std::sin(t), 0.2f * std::cos(0.7f * t), 0.1f * std::sin(1.3f * t), 0.0f};
  }
  return layout;
}

SimLayout with_ground(SimLayout layout) {
  float lowest = layout.x.front().y;
  for (const Float4& p : layout.x) lowest = std::min(lowest, p.y);
  layout.has_ground = true;
  layout.ground_y = lowest + 2e-3f;
  return layout;
}

SimLayout start_of(const std::string& name) {
  if (name == "cloth") return test::moving_cloth(16, 1e4, 1e-3, kH);
  if (name == "cloth over the ground") return with_ground(test::moving_cloth(16, 1e4, 1e-3, kH));
  if (name == "cloth, half dihedral, damped springs") {
    SimLayout layout = test::moving_cloth(16, 1e4, 1e-3, kH);
    for (std::size_t k = 0; k < layout.bend.size(); k += 2) layout.bend[k].model = ATS_BEND_DIHEDRAL;
    for (std::size_t k = 0; k < layout.stretch.size(); k += 3) layout.stretch[k].damping = 0.05f;
    return layout;
  }
  return moving_soft_box();
}

// x and v after kSubsteps of the plan on the whole CPU device.
std::pair<std::vector<Float4>, std::vector<Float4>> run_plan(const SimLayout& start, vbd::VbdOrdering ordering) {
  vertex::VertexBuffers ids;
  const auto plan = vbd::make_vbd_plan(start, kH, kIterations, &ids, ordering);
  const auto devices = device::DeviceSet::open("cpu");
  device::PlanExecutor exec(devices, plan);
  exec.run_substeps(kSubsteps);
  return {as_float4(exec.read(ids.x)), as_float4(exec.read(ids.v))};
}

}  // namespace

TEST_CASE("the OpenCL VBD plan and the host VBD reference agree to 1e-5 after a few substeps", "[vbd]") {
  const std::string scene = GENERATE("cloth", "cloth over the ground", "neo-Hookean solid");
  const bool lanes = GENERATE(false, true);  // solver.ordering colors or color_batches, on both sides
  INFO(scene << (lanes ? ", color_batches" : ", colors"));
  const SimLayout start = start_of(scene);
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
  const SimLayout start = start_of(scene);
  const auto colors = run_plan(start, vbd::VbdOrdering::colors);
  const auto lanes = run_plan(start, vbd::VbdOrdering::color_batches);
  CHECK(test::max_distance(colors.first, start.x) > 1e-4);  // it moved
  CHECK(std::memcmp(colors.first.data(), lanes.first.data(), colors.first.size() * sizeof(Float4)) == 0);
  CHECK(std::memcmp(colors.second.data(), lanes.second.data(), colors.second.size() * sizeof(Float4)) == 0);
}
