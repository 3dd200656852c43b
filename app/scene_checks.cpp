#include "app/scene_checks.hpp"

#include <fmt/format.h>

namespace atssim::app {

device::DeviceSet open_scene_devices(const scene::SceneDesc& scene) {
  try {
    return device::DeviceSet::open(scene.devices, device::parse_memory_mode(scene.memory));
  } catch (const Error& e) {
    // Only a spec written in the scene file itself names its line; a --set or
    // --devices override already names itself.
    if (e.setting() != Setting::devices || scene.devices_where.empty() ||
        scene.devices_where.find("(--set") != std::string::npos) {
      throw;
    }
    throw input_error(fmt::format("{}: devices {}", scene.devices_where, e.detail()));
  }
}

namespace {

// A method option whose value makes a one-device plan (MethodOption::one_device_from).
void check_one_device_options(const scene::SceneDesc& scene, const solver::MethodDescription& method,
                              const solver::MethodSettings& settings) {
  const std::string& schedule = scene.solver.schedule;
  if (schedule == "single") return;
  for (const solver::MethodOption& o : method.options) {
    if (o.one_device_from < 0 || settings.option(o.key) < o.one_device_from) continue;
    std::string where = scene.source_path;
    for (const scene::MethodOptionDesc& d : scene.solver.method_options) {
      if (d.key == o.key) where = d.where;
    }
    const auto choice = static_cast<std::size_t>(settings.option(o.key));
    throw input_error(
        fmt::format("{}: solver.{} '{}' orders the solve for one device, but schedule '{}' cuts or moves tasks between "
                    "devices; use schedule single with it, or another solver.{}",
                    where, o.key, o.choices[choice], schedule, o.key));
  }
}

}  // namespace

void check_schedule_fits(const scene::SceneDesc& scene, const solver::MethodDescription& method,
                         const solver::MethodSettings& settings, std::size_t devices) {
  const bool gauss_seidel = method.gauss_seidel;
  const std::string& schedule = scene.solver.schedule;
  const std::string where = scene.solver.schedule_where.empty() ? scene.source_path : scene.solver.schedule_where;
  check_one_device_options(scene, method, settings);
  if (schedule == "async" && !gauss_seidel) {
    throw input_error(fmt::format(
        "{}: schedule 'async' relaxes Gauss-Seidel iterations, and '{}' iterates Jacobi sweeps that already run on "
        "every device with one synchronisation each; use schedule split or heft",
        where, scene.solver.method));
  }
  if (schedule != "single" && devices < 2) {
    throw input_error(fmt::format(
        "{}: schedule '{}' needs at least two devices, but the device spec '{}' selects one; use e.g. devices "
        "cpu/2 (the CPU split into two sub-devices) or schedule single",
        where, schedule, scene.devices));
  }
}

std::string zero_compliance_line(const scene::SceneDesc& scene) {
  for (const scene::ObjectDesc& obj : scene.objects) {
    if (!obj.material.zero_compliance_where.empty()) return obj.material.zero_compliance_where;
  }
  return "";
}

}  // namespace atssim::app
