#pragma once
// The devices' cycle counters against the host clock (internal to
// lib/device): the fused dispatcher stamps tasks in device cycles, and a
// two-point calibration turns them into milliseconds on one clock.
#include <vector>

#include "device/device_set_impl.hpp"
#include "device/svm_arena.hpp"

namespace atssim::device {

struct CycleClock {
  double cycles_per_ms = 0.0;
  double ref_cycles = 0.0;  // a reading …
  double ref_ms = 0.0;      // … and the host time it was taken at (steady clock)
  double to_ms(double cycles) const { return ref_ms + (cycles - ref_cycles) / cycles_per_ms; }
};

// One per device of the set, or empty when its compiler has no cycle counter
// (or the counter does not advance). Where every device reads the host's own
// time-stamp counter (pocl's CPU devices on x86), the host calibrates it
// and all share that line, so their stamps compare exactly; else each device
// gets a two-point calibration from its launches, shared by devices whose
// readings fit one line. Measured once per set and process (~20 ms). For a
// set of one memory (the fused executor's).
const std::vector<CycleClock>& cycle_clocks(const DeviceSet::Impl& set, SvmArena& arena);

// Host steady clock in ms.
double host_ms();

}  // namespace atssim::device
