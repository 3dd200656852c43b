// The xpbd_tet kernel (StVK strain constraints) on the device, in float:
// a rest body stays at rest, and it agrees with the host reference.
#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>
#include <cstring>

#include "device/device_set.hpp"
#include "device/plan_executor.hpp"
#include "model/cloth_builder.hpp"
#include "scene/scene_loader.hpp"
#include "solver/xpbd/xpbd_reference.hpp"
#include "support/positions.hpp"

using namespace atssim;
using namespace atssim::solver;
using namespace atssim::solver::xpbd;
using atssim::test::max_distance;

namespace {

std::vector<Float4> as_float4(const std::vector<std::byte>& raw) {
  std::vector<Float4> out(raw.size() / sizeof(Float4));
  std::memcpy(out.data(), raw.data(), raw.size());
  return out;
}

model::Model stvk_box(const std::string& gravity, const std::string& size, const std::string& resolution, double youngs,
                      const std::string& pins) {
  const std::string yaml = "simulation: {gravity: " + gravity +
                           "}\n"
                           "objects:\n"
                           "  - type: solid\n"
                           "    box: {size: " +
                           size + ", resolution: " + resolution +
                           "}\n"
                           "    transform: {translate: [0.3, 1.0, -0.2], rotate: [10, 0, 30]}\n"
                           "    material: {density: 1000, youngs_modulus: " +
                           std::to_string(youngs) + ", poisson_ratio: 0.4, model: stvk}\n" + pins;
  return model::build_model(scene::parse_scene(yaml, "s.yaml", "."));
}

}  // namespace

TEST_CASE("a rest StVK box of many tets stays at rest to 1e-6 on the device without gravity", "[xpbd][tet]") {
  // The coupled Macklin-Mueller form drifted here; every strain constraint is
  // zero at rest on its own, so nothing has to cancel.
  const double youngs = GENERATE(5.0e4, 1.0e7);
  const std::string pins = GENERATE(std::string(""), std::string("    pins: {vertices: [0, 1, 2]}\n"));
  const auto m = stvk_box("[0, 0, 0]", "[0.4, 0.4, 0.4]", "[4, 4, 4]", youngs, pins);
  const SimLayout layout = make_sim_layout(m);
  REQUIRE(layout.tets.size() == 6 * 64);
  XpbdBuffers ids;
  const auto plan = make_xpbd_plan(layout, {1.0 / 960.0, 10}, &ids);
  const auto devices = device::DeviceSet::open("cpu");
  device::PlanExecutor exec(devices, plan);
  exec.run_substeps(30);
  const auto x = as_float4(exec.read(ids.x));
  const double drift = max_distance(x, layout.x);
  INFO("E " << youngs << (pins.empty() ? " free" : " pinned") << ": max drift after 30 substeps " << drift << " m");
  CHECK(drift < 1e-6);
}

TEST_CASE("the xpbd_tet kernel and the host reference agree to 1e-5 on a moving StVK bar", "[xpbd][tet]") {
  const char* svm = GENERATE("coarse", "fine");
  const int substeps = GENERATE(1, 4);
  const auto m =
      stvk_box("[0, -9.81, 0]", "[0.2, 1.0, 0.2]", "[2, 6, 2]", 1.0e5, "    pins: {vertices: [0, 1, 2, 3]}\n");
  const XpbdSettings settings{1.0 / 240.0, 8};
  SimLayout start = make_sim_layout(m);
  // A disturbed, moving state so that every constraint does work.
  for (std::size_t i = 0; i < start.v.size(); ++i) {
    if (start.x[i].w == 0.0f) continue;
    start.v[i] = {0.3f * std::sin(float(i)), 0.2f * std::cos(0.7f * float(i)), 0.1f, 0.0f};
  }
  XpbdBuffers ids;
  const auto plan = make_xpbd_plan(start, settings, &ids);
  const auto devices = device::DeviceSet::open("cpu");
  device::ExecutorOptions options;
  options.kind = device::ExecutorKind::events;
  options.svm = std::string(svm) == "coarse" ? device::SvmMode::coarse : device::SvmMode::fine;
  device::PlanExecutor exec(devices, plan, options);
  exec.run_substeps(substeps);
  const auto gpu_x = as_float4(exec.read(ids.x));
  const auto gpu_v = as_float4(exec.read(ids.v));

  XpbdReference ref(start, settings);
  for (int s = 0; s < substeps; ++s) ref.substep();
  REQUIRE(gpu_x.size() == ref.state().x.size());
  const double dx = max_distance(gpu_x, ref.state().x);
  const double dv = max_distance(gpu_v, ref.state().v);
  // How far the tets moved the particles away from free flight: the kernel
  // must have done real work for the comparison to mean anything.
  SimLayout free = start;
  free.tets.clear();
  free.tet_blocks.clear();
  XpbdReference unconstrained(free, settings);
  for (int s = 0; s < substeps; ++s) unconstrained.substep();
  const double work = max_distance(ref.state().x, unconstrained.state().x);
  INFO("svm " << svm << ", " << substeps << " substeps: max |dx| " << dx << " max |dv| " << dv
              << ", constraint correction " << work);
  CHECK(work > 1e-4);
  CHECK(dx < 1e-5);
  CHECK(dv < 1e-5 / settings.substep_dt);
}
