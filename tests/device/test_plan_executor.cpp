#include <catch2/catch.hpp>

#include <cmath>
#include <cstring>

#include "device/device_set.hpp"
#include "device/plan_executor.hpp"
#include "model/cloth_builder.hpp"
#include "scene/scene_loader.hpp"
#include "solver/xpbd/xpbd_reference.hpp"
#include "support/scenes.hpp"

using namespace atssim;
using namespace atssim::solver;
using namespace atssim::solver::xpbd;

namespace {

std::vector<Float4> as_float4(const std::vector<std::byte>& raw) {
  std::vector<Float4> out(raw.size() / sizeof(Float4));
  std::memcpy(out.data(), raw.data(), raw.size());
  return out;
}

// "events/coarse", "events/fine" or "fused" (fine grain with atomics).
device::ExecutorOptions options_of(const std::string& name) {
  device::ExecutorOptions o;
  o.kind = name == "fused" ? device::ExecutorKind::fused : device::ExecutorKind::events;
  o.svm = name == "events/coarse" ? device::SvmMode::coarse : device::SvmMode::fine;
  return o;
}

}  // namespace

TEST_CASE("the OpenCL kernels and the host reference agree to 1e-5 after one substep") {
  const std::string executor = GENERATE("events/coarse", "events/fine", "fused");
  const auto m = model::build_model(scene::parse_scene(test::hanging_cloth_yaml(16, 1e4, 1e-2), "s.yaml", "."));
  const XpbdSettings settings{1.0 / 240.0, 8};
  const SimLayout layout = make_sim_layout(m);
  XpbdBuffers ids;
  const auto plan = make_xpbd_plan(layout, settings, &ids);
  // Start from a disturbed, moving state so every term does work.
  SimLayout start = layout;
  for (std::size_t i = 0; i < start.v.size(); ++i) {
    start.v[i] = {0.3f * std::sin(float(i)), 0.2f * std::cos(0.7f * float(i)), 0.1f, 0.0f};
  }
  auto disturbed = make_xpbd_plan(start, settings);

  const auto devices = device::DeviceSet::open("cpu");
  device::PlanExecutor exec(devices, disturbed, options_of(executor));
  exec.run_substeps(1);
  const auto gpu_x = as_float4(exec.read(ids.x));
  const auto gpu_v = as_float4(exec.read(ids.v));

  XpbdReference ref(start, settings);
  ref.substep();
  REQUIRE(gpu_x.size() == ref.state().x.size());
  double max_dx = 0.0, max_dv = 0.0, moved = 0.0;
  for (std::size_t i = 0; i < gpu_x.size(); ++i) {
    const auto& a = gpu_x[i];
    const auto& b = ref.state().x[i];
    max_dx = std::max({max_dx, double(std::abs(a.x - b.x)), double(std::abs(a.y - b.y)), double(std::abs(a.z - b.z))});
    const auto& va = gpu_v[i];
    const auto& vb = ref.state().v[i];
    max_dv =
        std::max({max_dv, double(std::abs(va.x - vb.x)), double(std::abs(va.y - vb.y)), double(std::abs(va.z - vb.z))});
    moved = std::max(moved, double(std::abs(b.y - start.x[i].y)));
  }
  INFO(executor << ": max |dx| " << max_dx << " max |dv| " << max_dv);
  CHECK(moved > 1e-4);  // the substep really changed the state
  CHECK(max_dx < 1e-5);
  CHECK(max_dv < 1e-5 / settings.substep_dt);
}

TEST_CASE("without constraints the OpenCL XPBD reproduces discrete free fall to 1e-6") {
  const std::string yaml =
      "simulation: {gravity: [0.5, -9.81, 0.25]}\n"
      "objects:\n  - grid: {size: [0.01, 0.01], resolution: [3, 3]}\n";
  const auto m = model::build_model(scene::parse_scene(yaml, "s.yaml", "."));
  const double h = 1.0 / 960.0;
  XpbdBuffers ids;
  const auto plan = make_xpbd_plan(make_sim_layout(m), {h, 8}, &ids);
  CHECK(plan.graph.size() == 2);  // predict and update velocity only
  const auto devices = device::DeviceSet::open("cpu");
  device::PlanExecutor exec(devices, plan);
  const int n = 16;
  exec.run_substeps(n);
  const auto x = as_float4(exec.read(ids.x));
  const double k = h * h * n * (n + 1) / 2.0;
  for (std::size_t i = 0; i < m.particles.size(); ++i) {
    CHECK(x[i].x == Approx(m.particles.position[i].x() + k * 0.5).margin(1e-6));
    CHECK(x[i].y == Approx(m.particles.position[i].y() + k * -9.81).margin(1e-6));
    CHECK(x[i].z == Approx(m.particles.position[i].z() + k * 0.25).margin(1e-6));
  }
}

TEST_CASE("pinned particles never move on the device") {
  const auto m = model::build_model(scene::parse_scene(test::hanging_cloth_yaml(12), "s.yaml", "."));
  XpbdBuffers ids;
  const auto plan = make_xpbd_plan(make_sim_layout(m), {1.0 / 240.0, 8}, &ids);
  const auto devices = device::DeviceSet::open("cpu");
  device::PlanExecutor exec(devices, plan);
  exec.run_substeps(40);
  const auto x = as_float4(exec.read(ids.x));
  int pinned = 0;
  double lowest = 0.0;
  for (std::size_t i = 0; i < m.particles.size(); ++i) {
    lowest = std::min(lowest, double(x[i].y));
    if (m.particles.inv_mass[i] != 0.0) continue;
    ++pinned;
    CHECK(x[i].x == float(m.particles.position[i].x()));
    CHECK(x[i].y == float(m.particles.position[i].y()));
    CHECK(x[i].z == float(m.particles.position[i].z()));
  }
  CHECK(pinned == 2);
  CHECK(lowest < -0.05);  // the rest of the cloth fell
}
