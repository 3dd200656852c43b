#pragma once
// What moving a task's output between two devices costs (paper §3.3.1).
// For an edge of weight w from device p to device q:
//   comm = 0                                       if p == q
//   comm = latency_ms[p][q] + w · ms_per_weight[p][q]   otherwise.
// Unified memory (the paper's Apple SoCs, SVM on one OpenCL context) is a
// fixed delay per hop: latency = delay, ms_per_weight = 0. Non-unified memory
// adds a transfer that grows with the data: w = bytes, ms_per_weight = 1 /
// bandwidth. The classic HEFT setting (Topcuoglu 2002) is latency 0,
// ms_per_weight 1: the edge weight *is* the cost.
#include <cstddef>
#include <vector>

#include "sched/ids.hpp"

namespace atssim::sched {

struct DeviceLinks {
  std::size_t devices = 0;
  std::vector<double> latency_ms;     // [from * devices + to]; diagonal unused
  std::vector<double> ms_per_weight;  // [from * devices + to]; 0 = weight ignored

  // Every cross-device hop costs `delay_ms`, whatever the edge weight.
  static DeviceLinks unified_memory(std::size_t devices, double delay_ms);
  // Every cross-device hop costs latency_ms + weight · ms_per_weight.
  static DeviceLinks weighted(std::size_t devices, double latency_ms = 0.0, double ms_per_weight = 1.0);

  void set_link(DeviceId from, DeviceId to, double latency, double per_weight);

  double comm_ms(double weight, DeviceId from, DeviceId to) const {
    if (from == to) return 0.0;
    const std::size_t i = from * devices + to;
    return latency_ms[i] + weight * ms_per_weight[i];
  }
};

}  // namespace atssim::sched
