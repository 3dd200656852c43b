#pragma once
// Copies between devices that share no memory (internal to lib/device;
// DESIGN.md "Devices", non-unified memory). Each device holds its own copy
// of every buffer; the transfer plan (plan/transfer_plan.hpp) says which
// elements move when. A copy goes device → host staging → device: the
// producer's queue copies out right after the producer (a contiguous run
// directly, scattered elements through a gather kernel into a packed
// buffer), a callback on that copy completes a user event in the consumer's
// context, and the consumer's queue copies in (and scatters), waiting for
// it, before the consumer. Events of one context
// cannot be waited on in another, so every dependency between devices goes
// through such a user event — also the substep barrier (each device's first
// task waits for every other device's last command of the substep before).
#include <cstddef>
#include <memory>
#include <vector>

#include "device/executor_parts.hpp"
#include "plan/transfer_plan.hpp"
#include "sched/task_timing.hpp"

namespace atssim::device {

class MemoryCopies {
 public:
  // Plans the copies of one substep of `steps` (every device its own memory).
  MemoryCopies(const PlanResources& resources, const std::vector<Step>& steps);
  MemoryCopies(const MemoryCopies&) = delete;
  MemoryCopies& operator=(const MemoryCopies&) = delete;
  ~MemoryCopies();

  const plan::TransferPlan& transfers() const { return transfers_; }

  // Called in step order while a substep is enqueued. Before step s runs on
  // its device: its first command must wait for `wait` (the barrier of the
  // substep before, for a device's first step); the copies into it are
  // enqueued here, and `wait` is emptied once a command carries it.
  void before_step(std::size_t s, std::vector<cl_event>& wait);
  // After step s's kernels: the copies out of it.
  void after_step(std::size_t s);
  // After the last step: the boundary copies, then each device's end-of-
  // substep signal; returns, per device, what its next first step waits for.
  std::vector<std::vector<cl_event>> end_substep();

  // Bytes copied (counted once per transfer, as they leave) since the last call.
  std::size_t take_bytes();
  // Each copy of the last substep enqueued with `record`: bytes and time.
  void record_next_substep() { recording_ = true; }
  std::vector<sched::CopyTiming> recorded();
  // Events to release once every queue is finished.
  std::vector<cl_event>& graveyard() { return graveyard_; }

 private:
  struct Staged;
  std::unique_ptr<Staged> stage(const plan::Transfer& t);
  void copy_out(const plan::Transfer& t, Staged& s);
  void copy_in(const plan::Transfer& t, Staged& s, std::vector<cl_event>& wait);

  const PlanResources& r_;
  std::vector<Step> steps_;
  plan::TransferPlan transfers_;
  std::vector<std::unique_ptr<Staged>> within_, boundary_;
  std::vector<std::vector<std::size_t>> in_at_, out_at_;  // per step: within transfers into / out of it
  std::vector<std::size_t> last_step_;                    // per device, or npos
  std::size_t bytes_ = 0;
  bool recording_ = false;
  std::vector<cl_event> graveyard_;
  std::vector<cl::Program> copy_programs_;  // per memory (kernels/device/copy.cl)
};

// Device `from`'s memory to device `to`'s through host staging, the way the
// copies above go: the median time of a small copy (latency) and the time
// per byte of a large one, over `repetitions`.
struct LinkMeasurement {
  double latency_ms = 0.0;
  double ms_per_byte = 0.0;
};
LinkMeasurement measure_link(const PlanResources& resources, std::size_t from, std::size_t to, int repetitions);

}  // namespace atssim::device
