#pragma once
// The scheduler's output (DESIGN.md "Output"): per device an ordered list of
// slots with predicted start and finish, the makespan, and the cross-device
// waits an executor with one in-order queue per device must insert.
#include <cstdint>
#include <limits>
#include <string>
#include <vector>

#include "sched/cost_table.hpp"
#include "sched/device_links.hpp"
#include "sched/task_graph.hpp"

namespace atssim::sched {

struct Slot {
  TaskId task = 0;
  double start_ms = 0.0;
  double finish_ms = 0.0;
};

inline constexpr DeviceId kNoDevice = std::numeric_limits<DeviceId>::max();

struct Placement {
  DeviceId device = kNoDevice;  // kNoDevice: the task is not in the schedule
  std::uint32_t index = 0;      // position in devices[device]
};

// Queue `consumer_device` must wait, before `consumer`, for `producer` to
// complete on `producer_device`.
struct Wait {
  TaskId producer = 0;
  DeviceId producer_device = 0;
  TaskId consumer = 0;
  DeviceId consumer_device = 0;

  friend bool operator==(const Wait&, const Wait&) = default;
};

struct Schedule {
  std::vector<std::vector<Slot>> devices;  // per device, slots ordered by start
  std::vector<Placement> placement;        // per task
  std::vector<double> device_ready_ms;     // per device: busy until then (re-scheduling at t0)
  std::vector<TaskId> scheduling_order;    // order in which the list scheduler placed tasks
  double makespan_ms = 0.0;                // latest finish (absolute: t0 included)

  std::size_t task_count() const { return placement.size(); }
  const Slot& slot(TaskId task) const;
  DeviceId device_of(TaskId task) const { return placement.at(task).device; }

  // The minimal set of cross-device waits. An edge u → v with u on p and
  // v on q ≠ p needs queue q to wait for u, unless that is already implied:
  // by an earlier wait on q for u or a later task of p's in-order queue, or
  // transitively through waits on other queues (vector clocks over the
  // queues). So tasks in a row on q that read from p share one wait
  // (paper §3.3.3: consecutive same-device tasks share one sync).
  // Sorted by consumer device, consumer position, producer device.
  std::vector<Wait> cross_device_waits(const TaskGraph& graph) const;

  // Every problem found, one human-readable line each; empty when valid.
  // Checks: each task placed exactly once on a device that can run it, for
  // exactly its cost, not before the device's ready time; slots ordered and
  // not overlapping; each edge's consumer starts after the producer's finish
  // plus the communication delay; the makespan is the latest finish.
  // Times compare with a tolerance of 1e-9 · max(1, makespan).
  std::vector<std::string> validate(const TaskGraph& graph, const CostTable& costs, const DeviceLinks& links) const;
  // Throws atssim::Error (internal: a scheduler broke its promise) listing the problems, if any.
  void throw_if_invalid(const TaskGraph& graph, const CostTable& costs, const DeviceLinks& links) const;
};

// Builds a Schedule from per-device slot lists (any order): sorts each list
// by start, fills `placement` and the makespan. Used by the schedulers, by
// tests, and to turn measured start/finish times back into a Schedule.
Schedule assemble_schedule(std::size_t task_count, std::vector<std::vector<Slot>> devices,
                           std::vector<double> device_ready_ms = {});

// The replay of an async schedule (solver.replay): every task on device 0
// alone, in the order of its predicted start in `schedule` (ties keep task
// order), each for its cost on device 0; the other `devices` lanes empty.
Schedule replay_on_device0(const Schedule& schedule, const CostTable& costs, std::size_t devices);

}  // namespace atssim::sched
