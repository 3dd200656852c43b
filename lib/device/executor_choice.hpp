#pragma once
// Which executor runs a plan (DESIGN.md "Devices"): a pure decision on the
// devices' capability records, so it is tested without OpenCL.
#include <span>
#include <string>
#include <string_view>

#include "device/device_info.hpp"

namespace atssim::device {

enum class ExecutorKind { automatic, events, fused };

// "auto", "events", "fused"; anything else is an input error listing them.
ExecutorKind parse_executor_kind(const std::string& text);
std::string_view to_string(ExecutorKind kind);

// Why a device cannot run the fused executor ("" when it can): the
// dispatchers of all devices synchronise through atomics in fine-grain
// buffer SVM while they run.
std::string fused_obstacle(const DeviceInfo& device);

// `automatic` becomes fused when every device can run it and all share one
// memory (`memories` contexts: fused waits are atomics in one SVM), else
// events; events stays events. Fused asked for where it cannot run is an
// input error naming the device and what it lacks, or the memories.
ExecutorKind choose_executor(ExecutorKind requested, std::span<const DeviceInfo> devices, std::size_t memories = 1);

}  // namespace atssim::device
