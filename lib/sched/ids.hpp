#pragma once
// Task and device ids used throughout the scheduler: plain indices into the
// task graph and into the cost table's device columns.
#include <cstdint>

namespace atssim::sched {

using TaskId = std::uint32_t;
using DeviceId = std::uint32_t;

}  // namespace atssim::sched
