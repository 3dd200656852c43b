// solver.ordering: batches on the device (kernels/xpbd/xpbd.cl, *_batches)
// against the host XPBD reference sweeping the same constraint order.
#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>

#include "device/device_set.hpp"
#include "device/plan_executor.hpp"
#include "model/cloth_builder.hpp"
#include "plan/buffer.hpp"
#include "scene/scene_loader.hpp"
#include "solver/xpbd/xpbd_batches.hpp"
#include "solver/xpbd/xpbd_reference.hpp"
#include "support/scenes.hpp"

using namespace atssim;
using namespace atssim::solver;
using namespace atssim::solver::xpbd;

namespace {

double max_difference(const std::vector<Float4>& a, const std::vector<Float4>& b) {
  double d = 0.0;
  for (std::size_t i = 0; i < a.size(); ++i) {
    d = std::max(
        {d, double(std::abs(a[i].x - b[i].x)), double(std::abs(a[i].y - b[i].y)), double(std::abs(a[i].z - b[i].z))});
  }
  return d;
}

// A 16 x 16 hanging cloth with `material` keys added, in a disturbed, moving
// state so that every constraint does work.
SimLayout moving_cloth(const std::string& material) {
  std::string yaml = test::hanging_cloth_yaml(16, 1e4, 1e-2);
  yaml.replace(yaml.find("material: {") + 11, 0, material);
  SimLayout start = make_sim_layout(model::build_model(scene::parse_scene(yaml, "s.yaml", ".")));
  for (std::size_t i = 0; i < start.v.size(); ++i) {
    start.v[i] = {0.3f * std::sin(float(i)), 0.2f * std::cos(0.7f * float(i)), 0.1f, 0.0f};
  }
  return start;
}

// A StVK bar (6 · 3 · 12 · 3 tets) moving in a disturbed state.
SimLayout moving_bar() {
  SimLayout start = make_sim_layout(model::build_model(scene::parse_scene(test::stvk_bar_yaml(3), "s.yaml", ".")));
  for (std::size_t i = 0; i < start.v.size(); ++i) {
    if (start.x[i].w == 0.0f) continue;
    start.v[i] = {0.3f * std::sin(float(i)), 0.2f * std::cos(0.7f * float(i)), 0.1f, 0.0f};
  }
  return start;
}

// The positions after one substep of `start` under `settings` on the device.
std::vector<Float4> device_substep(const SimLayout& start, const XpbdSettings& settings, const std::string& executor) {
  XpbdBuffers ids;
  const auto plan = make_xpbd_plan(start, settings, &ids);
  device::ExecutorOptions options;
  options.kind = executor == "fused" ? device::ExecutorKind::fused : device::ExecutorKind::events;
  const auto devices = device::DeviceSet::open("cpu");
  device::PlanExecutor exec(devices, plan, options);
  exec.run_substeps(1);
  return plan::values_of<Float4>(exec.read(ids.x));
}

}  // namespace

TEST_CASE("the batched sweep on the device equals the host serial loop over the same order to 1e-5") {
  const std::string executor = GENERATE("events", "fused");
  // Undamped springs and isometric stencils take the float8 lanes; damped
  // springs and dihedral stencils the scalar ones (kernels/xpbd/xpbd.cl).
  const std::string material = GENERATE(std::string(), std::string("bend_model: dihedral, damping: 0.01, "));
  // One iteration: after a single sweep the order shows (8 converge to ~1e-7 of each other).
  const XpbdSettings settings{1.0 / 240.0, 1, XpbdOrdering::batches};
  const SimLayout start = moving_cloth(material);
  const auto device_x = device_substep(start, settings, executor);

  XpbdReference same_order(in_batch_order(start), {settings.substep_dt, settings.iterations});
  same_order.substep();
  XpbdReference colors(start, {settings.substep_dt, settings.iterations});
  colors.substep();

  const double to_same = max_difference(device_x, same_order.state().x);
  const double to_colors = max_difference(device_x, colors.state().x);
  INFO(executor << " " << material << ": max |dx| to the same order " << to_same << ", to the color order "
                << to_colors);
  CHECK(to_same < 1e-5);
  // The order matters: the color order's result is farther than the tolerance.
  CHECK(to_colors > 10 * to_same);
  CHECK(to_colors > 1e-5);
}

TEST_CASE("color batches on the device equal the host color loop to 1e-5") {
  const std::string executor = GENERATE("events", "fused");
  // Undamped springs and isometric stencils, then damped springs (their own
  // float8 lanes) and dihedral stencils (the scalar lanes).
  const std::string material = GENERATE(std::string(), std::string("bend_model: dihedral, damping: 0.01, "));
  const XpbdSettings settings{1.0 / 240.0, 2, XpbdOrdering::color_batches};
  const SimLayout start = moving_cloth(material);
  const auto device_x = device_substep(start, settings, executor);

  // The second implementation: the host reference's scalar loop in the color order.
  XpbdReference colors(start, {settings.substep_dt, settings.iterations});
  colors.substep();
  const double to_colors = max_difference(device_x, colors.state().x);
  INFO(executor << " " << material << ": max |dx| to the host color loop " << to_colors);
  CHECK(to_colors < 1e-5);
}

TEST_CASE("StVK tets as float8 lanes equal the host scalar loop in the same order to 1e-5") {
  const std::string executor = GENERATE("events", "fused");
  const SimLayout start = moving_bar();
  REQUIRE(start.tets.size() == 6 * 3 * 12 * 3);
  // color_batches: the color order, each block cut into batches of 8 tets.
  const XpbdSettings lanes{1.0 / 240.0, 2, XpbdOrdering::color_batches};
  XpbdReference colors(start, {lanes.substep_dt, lanes.iterations});
  colors.substep();
  const double to_colors = max_difference(device_substep(start, lanes, executor), colors.state().x);
  // batches: NvCloth's batches swept in one task, against the host loop over that order.
  const XpbdSettings sweep{1.0 / 240.0, 1, XpbdOrdering::batches};
  XpbdReference same_order(in_batch_order(start), {sweep.substep_dt, sweep.iterations});
  same_order.substep();
  XpbdReference color_order(start, {sweep.substep_dt, sweep.iterations});
  color_order.substep();
  const auto swept = device_substep(start, sweep, executor);
  const double to_same = max_difference(swept, same_order.state().x);
  const double moved = max_difference(start.x, colors.state().x);
  INFO(executor << ": max |dx| color_batches to the host color loop " << to_colors << ", batches to the host loop in "
                << "their order " << to_same << ", to the color order " << max_difference(swept, color_order.state().x)
                << "; the substep moved particles up to " << moved << " m");
  CHECK(moved > 1e-4);  // 50 times the tolerance below
  CHECK(to_colors < 1e-5);
  CHECK(to_same < 1e-5);
  CHECK(max_difference(swept, color_order.state().x) > 10 * to_same);
}
