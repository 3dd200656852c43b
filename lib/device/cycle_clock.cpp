#include "device/cycle_clock.hpp"

#include <chrono>
#include <cmath>
#include <map>
#include <mutex>
#include <thread>

#include "device/program_builder.hpp"
#include "util/error.hpp"

#if defined(__x86_64__) || defined(__i386__)
#include <x86intrin.h>
#define ATSSIM_HOST_TSC 1
#endif

namespace atssim::device {

namespace {

struct Reading {
  double cycles = 0.0;
  double ms = 0.0;          // midpoint of the launch's bracket
  double half_width = 0.0;  // half the bracket: how far off `ms` may be
};

Reading read_counter(const cl::CommandQueue& queue, const cl::Kernel& kernel, const cl_ulong* out) {
  const std::size_t one = 1;
  const double before = host_ms();
  check_cl(clEnqueueNDRangeKernel(queue(), kernel(), 1, nullptr, &one, &one, 0, nullptr, nullptr),
           "enqueueing the clock probe");
  check_cl(clFinish(queue()), "waiting for the clock probe");
  const double after = host_ms();
  return {static_cast<double>(*out), 0.5 * (before + after), 0.5 * (after - before)};
}

#ifdef ATSSIM_HOST_TSC
// Whether every device reads the host's own time-stamp counter (pocl's CPU
// devices run on this host: their cycle counter is its TSC): each device's
// reading falls between two host readings around its launch.
bool devices_read_host_tsc(const DeviceSet::Impl& set, const cl::Kernel& kernel, const cl_ulong* out) {
  const std::size_t one = 1;
  for (const auto& q : set.queues) {
    bool inside = false;
    for (int attempt = 0; attempt < 3 && !inside; ++attempt) {
      const unsigned long long before = __rdtsc();
      check_cl(clEnqueueNDRangeKernel(q(), kernel(), 1, nullptr, &one, &one, 0, nullptr, nullptr),
               "enqueueing the clock probe");
      check_cl(clFinish(q()), "waiting for the clock probe");
      const unsigned long long after = __rdtsc();
      inside = *out >= before && *out <= after;
    }
    if (!inside) return false;
  }
  return true;
}

// The host TSC against the steady clock, over `ms` of sleep.
CycleClock host_tsc_clock(int ms) {
  const unsigned long long c0 = __rdtsc();
  const double t0 = host_ms();
  std::this_thread::sleep_for(std::chrono::milliseconds(ms));
  const unsigned long long c1 = __rdtsc();
  const double t1 = host_ms();
  return {static_cast<double>(c1 - c0) / (t1 - t0), static_cast<double>(c1), t1};
}
#endif

std::vector<CycleClock> calibrate(const DeviceSet::Impl& set, SvmArena& arena) {
  cl::Program program;
  try {
    program = build_program(set.contexts.at(0), set.devices, "clock_probe", "-cl-std=CL2.0");
  } catch (const Error&) {
    return {};  // no cycle counter in this compiler
  }
  cl::Kernel kernel(program, "probe_clock");
  auto* out = static_cast<cl_ulong*>(arena.allocate(sizeof(cl_ulong)));
  check_cl(clSetKernelArgSVMPointer(kernel(), 0, out), "setting the clock probe's argument");
  std::vector<Reading> first, second;
  for (const auto& q : set.queues) read_counter(q, kernel, out);  // warm-up: the first launch compiles
#ifdef ATSSIM_HOST_TSC
  // One counter for every device and the host: calibrate it on the host,
  // where no launch jitter blurs the readings, and share the line.
  if (devices_read_host_tsc(set, kernel, out)) {
    arena.release(out);
    return std::vector<CycleClock>(set.queues.size(), host_tsc_clock(20));
  }
#endif
  for (const auto& q : set.queues) first.push_back(read_counter(q, kernel, out));
  std::this_thread::sleep_for(std::chrono::milliseconds(20));
  for (const auto& q : set.queues) second.push_back(read_counter(q, kernel, out));
  arena.release(out);

  std::vector<CycleClock> clocks;
  for (std::size_t d = 0; d < set.queues.size(); ++d) {
    const double rate = (second[d].cycles - first[d].cycles) / (second[d].ms - first[d].ms);
    if (!(rate > 0.0) || !std::isfinite(rate) || second[d].cycles == 0.0) return {};
    CycleClock c{rate, second[d].cycles, second[d].ms};
    // One counter for both (a CPU's sub-devices): device 0's line predicts
    // this reading within the launch bracket. Then use that line, so the
    // stamps of both devices compare without the brackets' jitter.
    if (d > 0) {
      const CycleClock& c0 = clocks.front();
      if (std::abs(c0.to_ms(second[d].cycles) - second[d].ms) <= second[0].half_width + second[d].half_width + 0.01 &&
          std::abs(rate / c0.cycles_per_ms - 1.0) < 0.01) {
        c = c0;
      }
    }
    clocks.push_back(c);
  }
  return clocks;
}

}  // namespace

double host_ms() {
  return std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now().time_since_epoch()).count();
}

const std::vector<CycleClock>& cycle_clocks(const DeviceSet::Impl& set, SvmArena& arena) {
  // Like the contexts (device_set.hpp), kept for the whole process.
  static auto* cache = new std::map<const DeviceSet::Impl*, std::vector<CycleClock>>();
  static std::mutex mutex;
  const std::lock_guard<std::mutex> lock(mutex);
  auto it = cache->find(&set);
  if (it == cache->end()) it = cache->emplace(&set, calibrate(set, arena)).first;
  return it->second;
}

}  // namespace atssim::device
