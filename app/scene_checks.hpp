#pragma once
// Scene-level settings that only the later stages can judge (a schedule
// the devices or the method cannot run, a device spec that selects nothing,
// a perfectly stiff material a method cannot take) are reported at the
// scene line that asked for them, not as if a CLI flag had been wrong.
#include <cstddef>
#include <functional>

#include "device/device_set.hpp"
#include "scene/scene_desc.hpp"
#include "solver/method.hpp"

namespace atssim::app {

// DeviceSet::open on the scene's spec; its input errors name the scene line
// (or the --set / --devices) that gave the spec.
device::DeviceSet open_scene_devices(const scene::SceneDesc& scene);

// Throws atssim::Error (input) at solver.schedule's line when the schedule
// needs two devices and `devices` is one, or is async and the method
// iterates Jacobi sweeps; at a method option's line when its value makes a
// one-device plan (MethodOption::one_device_from) and the schedule is not single.
void check_schedule_fits(const scene::SceneDesc& scene, const solver::MethodDescription& method,
                         const solver::MethodSettings& settings, std::size_t devices);

// Runs `build` (a plan builder); an input error it raises about a perfectly
// stiff constraint is given the scene line of the compliance of 0.
template <typename Build>
auto with_stiffness_line(const scene::SceneDesc& scene, Build build) -> decltype(build());

std::string zero_compliance_line(const scene::SceneDesc& scene);

}  // namespace atssim::app

#include "util/error.hpp"

namespace atssim::app {

template <typename Build>
auto with_stiffness_line(const scene::SceneDesc& scene, Build build) -> decltype(build()) {
  try {
    return build();
  } catch (const Error& e) {
    const std::string where = zero_compliance_line(scene);
    if (e.setting() != Setting::compliance || where.empty()) throw;
    throw input_error(where + ": " + e.detail());
  }
}

}  // namespace atssim::app
