#include "app/scene_checks.hpp"

#include <fmt/format.h>

namespace atssim::app {

device::DeviceSet open_scene_devices(const scene::SceneDesc& scene) {
  try {
    return device::DeviceSet::open(scene.devices, device::parse_memory_mode(scene.memory));
  } catch (const Error& e) {
    const std::string what = e.what();
    const std::string flag = "--devices '";
    // Only a spec written in the scene file itself names its line; a --set or
    // --devices override already names itself.
    if (e.kind() != ErrorKind::input || scene.devices_where.empty() || what.rfind(flag, 0) != 0 ||
        scene.devices_where.find("(--set") != std::string::npos) {
      throw;
    }
    throw input_error(fmt::format("{}: devices '{}", scene.devices_where, what.substr(flag.size())));
  }
}

void check_schedule_fits(const scene::SceneDesc& scene, bool gauss_seidel, std::size_t devices) {
  const std::string& schedule = scene.solver.schedule;
  const std::string where = scene.solver.schedule_where.empty() ? scene.source_path : scene.solver.schedule_where;
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
