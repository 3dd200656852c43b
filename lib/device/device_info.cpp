#include "device/device_info.hpp"

#include <fmt/format.h>

#include "device/device_query.hpp"
#include "device/opencl.hpp"

namespace atssim::device {

std::vector<DeviceInfo> list_devices() {
  std::vector<DeviceInfo> out;
  for (const DeviceHandle& h : all_device_handles()) out.push_back(h.info);
  return out;
}

std::string svm_text(const SvmCaps& caps) {
  if (!caps.any()) return "none";
  std::string s;
  auto add = [&](bool on, const char* name) {
    if (!on) return;
    if (!s.empty()) s += "+";
    s += name;
  };
  add(caps.coarse_buffer, "coarse");
  add(caps.fine_buffer, "fine");
  add(caps.fine_system, "system");
  add(caps.atomics, "atomics");
  return s;
}

std::string describe(const DeviceInfo& d) {
  std::string split = d.max_sub_devices >= 2 ? fmt::format(", splits into ≤{}", d.max_sub_devices) : "";
  return fmt::format("{} ({}:{}): {} [{}] — {}, {} compute units, {:.1f} GiB, {}, {}, SVM {}{}", d.index,
                     d.platform_index, d.platform_device, d.name, d.platform, d.type, d.compute_units,
                     d.global_memory / double(1 << 30), d.version, d.c_version, svm_text(d.svm), split);
}

}  // namespace atssim::device
