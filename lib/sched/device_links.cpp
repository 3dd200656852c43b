#include "sched/device_links.hpp"

#include <fmt/format.h>

#include "util/error.hpp"

namespace atssim::sched {

DeviceLinks DeviceLinks::unified_memory(std::size_t devices, double delay_ms) {
  return weighted(devices, delay_ms, 0.0);
}

DeviceLinks DeviceLinks::weighted(std::size_t devices, double latency, double per_weight) {
  DeviceLinks links;
  links.devices = devices;
  links.latency_ms.assign(devices * devices, latency);
  links.ms_per_weight.assign(devices * devices, per_weight);
  for (std::size_t d = 0; d < devices; ++d) {
    links.latency_ms[d * devices + d] = 0.0;
    links.ms_per_weight[d * devices + d] = 0.0;
  }
  return links;
}

void DeviceLinks::set_link(DeviceId from, DeviceId to, double latency, double per_weight) {
  if (from >= devices || to >= devices) {
    throw internal_error(
        fmt::format("device links: link {} -> {} names a device that does not exist "
                    "({} devices)",
                    from, to, devices));
  }
  if (!(latency >= 0.0) || !(per_weight >= 0.0)) {
    throw internal_error(
        fmt::format("device links: link {} -> {} needs latency and ms per weight >= 0, "
                    "got {} and {}",
                    from, to, latency, per_weight));
  }
  latency_ms[from * devices + to] = latency;
  ms_per_weight[from * devices + to] = per_weight;
}

}  // namespace atssim::sched
