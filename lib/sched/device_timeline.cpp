#include "sched/device_timeline.hpp"

#include <algorithm>
#include <limits>

#include "util/error.hpp"

namespace atssim::sched {

DeviceTimeline::DeviceTimeline(double ready_ms, double shortest_task_ms)
    : gaps_{{ready_ms, std::numeric_limits<double>::infinity()}}, shortest_(shortest_task_ms) {}

double DeviceTimeline::earliest_start(double ready, double duration, bool insertion) const {
  if (!insertion) return std::max(ready, gaps_.back().start);
  // First gap that ends after `ready`; earlier ones cannot hold the task.
  auto it = std::upper_bound(gaps_.begin(), gaps_.end(), ready, [](double r, const Gap& g) { return r < g.end; });
  for (; it != gaps_.end(); ++it) {
    const double start = std::max(it->start, ready);
    if (start + duration <= it->end) return start;
  }
  return std::max(ready, gaps_.back().start);  // unreachable: the last gap is open
}

void DeviceTimeline::reserve(double start, double finish) {
  // The gap holding `start`: the last one that begins at or before it.
  auto it = std::upper_bound(gaps_.begin(), gaps_.end(), start, [](double s, const Gap& g) { return s < g.start; });
  if (it == gaps_.begin() || finish > std::prev(it)->end || finish < start) {
    throw internal_error("device timeline: reserved interval is not inside an idle gap");
  }
  --it;
  const Gap before{it->start, start};
  const Gap after{finish, it->end};
  const bool keep_before = before.end - before.start >= shortest_ && before.end > before.start;
  const bool is_last = std::next(it) == gaps_.end();
  const bool keep_after = is_last || (after.end - after.start >= shortest_ && after.end > after.start);
  if (keep_before && keep_after) {
    *it = after;
    gaps_.insert(it, before);
  } else if (keep_before) {
    *it = before;
  } else if (keep_after) {
    *it = after;
  } else {
    gaps_.erase(it);
  }
}

}  // namespace atssim::sched
