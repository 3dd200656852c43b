#pragma once
// The idle gaps of one device while a list scheduler fills it (Topcuoglu
// 2002 §4.1, "insertion-based policy"; paper §3.3.3: "identifies the optimal
// insertion point in each processor's queue").
//
// Kept as a sorted list of disjoint gaps; the last one is [end, +inf). A gap
// shorter than the shortest task that could ever run on the device is
// dropped at once, so long schedules do not accumulate unusable slivers.
// A query costs a binary search plus a scan over the gaps after the ready
// time that are too short; list schedulers work near the end of the
// timeline, so that scan is short in practice (worst case linear).
#include <vector>

namespace atssim::sched {

class DeviceTimeline {
 public:
  // The device is busy until `ready_ms`; gaps shorter than
  // `shortest_task_ms` can never be used.
  explicit DeviceTimeline(double ready_ms = 0.0, double shortest_task_ms = 0.0);

  // Earliest start >= ready for a task of `duration` ms. With insertion,
  // the first idle gap that fits; without, after the last placed task.
  double earliest_start(double ready, double duration, bool insertion) const;

  // Marks [start, finish) busy. It must lie inside one idle gap (as
  // returned by earliest_start).
  void reserve(double start, double finish);

  // Finish of the last placed task (or the ready time when none).
  double end() const { return gaps_.back().start; }
  std::size_t gap_count() const { return gaps_.size(); }

 private:
  struct Gap {
    double start;
    double end;
  };
  std::vector<Gap> gaps_;
  double shortest_;
};

}  // namespace atssim::sched
