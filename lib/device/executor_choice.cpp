#include "device/executor_choice.hpp"

#include <fmt/format.h>

#include "util/error.hpp"

namespace atssim::device {

ExecutorKind parse_executor_kind(const std::string& text) {
  if (text == "auto" || text == "automatic") return ExecutorKind::automatic;
  if (text == "events") return ExecutorKind::events;
  if (text == "fused") return ExecutorKind::fused;
  throw input_error(
      fmt::format("unknown executor '{}'; use auto (fused where the devices allow it), fused (one "
                  "launch per device and frame) or events (one launch per task)",
                  text));
}

std::string_view to_string(ExecutorKind kind) {
  switch (kind) {
    case ExecutorKind::automatic:
      return "auto";
    case ExecutorKind::events:
      return "events";
    case ExecutorKind::fused:
      return "fused";
  }
  return "?";
}

std::string fused_obstacle(const DeviceInfo& d) {
  if (!d.svm.fine_buffer) return "no fine-grain buffer SVM";
  if (!d.svm.atomics) return "no SVM atomics";
  return "";
}

ExecutorKind choose_executor(ExecutorKind requested, std::span<const DeviceInfo> devices, std::size_t memories) {
  if (requested == ExecutorKind::events) return ExecutorKind::events;
  if (memories > 1) {
    if (requested == ExecutorKind::automatic) return ExecutorKind::events;
    throw input_error(
        fmt::format("executor 'fused' synchronises the devices through one shared memory, and these {} "
                    "devices have {} memories (separate memories, or several platforms); use "
                    "--executor events",
                    devices.size(), memories));
  }
  for (const DeviceInfo& d : devices) {
    const std::string why = fused_obstacle(d);
    if (why.empty()) continue;
    if (requested == ExecutorKind::automatic) return ExecutorKind::events;
    throw input_error(
        fmt::format("executor 'fused' needs fine-grain buffer SVM with atomics on every device, and "
                    "device {} ({}) has {}; use --executor events",
                    d.index, d.name, why));
  }
  return devices.empty() ? ExecutorKind::events : ExecutorKind::fused;
}

}  // namespace atssim::device
