#include "device/event_runner.hpp"

#include <algorithm>
#include <limits>

#include <fmt/format.h>

#include "device/memory_copies.hpp"
#include "device/program_builder.hpp"
#include "util/error.hpp"

namespace atssim::device {

namespace {

struct PreparedLaunch {
  cl::Kernel kernel;
  std::size_t global = 0;
};

// A step as the queues need it: which events it waits for and produces.
struct QueuedStep {
  sched::TaskId task = 0;
  std::size_t device = 0;
  std::vector<sched::TaskId> waits;
  bool event_needed = false;  // another queue waits for it
  bool first_on_device = false;
};

class EventList {
 public:
  EventList() = default;
  EventList(const EventList&) = delete;
  EventList& operator=(const EventList&) = delete;
  ~EventList() { clear(); }
  void resize(std::size_t n) { events_.assign(n, nullptr); }
  cl_event& operator[](std::size_t i) { return events_[i]; }
  cl_event operator[](std::size_t i) const { return events_[i]; }
  void clear() {
    for (cl_event& e : events_) {
      if (e != nullptr) clReleaseEvent(e);
      e = nullptr;
    }
  }
  void swap(EventList& other) noexcept { events_.swap(other.events_); }
  // Hands every event to `graveyard` (to be released later) and empties the list.
  void retire_into(std::vector<cl_event>& graveyard) {
    for (cl_event& e : events_) {
      if (e != nullptr) graveyard.push_back(e);
      e = nullptr;
    }
  }

 private:
  std::vector<cl_event> events_;
};

double event_ns(cl_event e, cl_profiling_info what) {
  cl_ulong t = 0;
  check_cl(clGetEventProfilingInfo(e, what, sizeof(t), &t, nullptr), "reading an OpenCL profiling event");
  return static_cast<double>(t);
}

}  // namespace

struct EventRunner::Impl {
  const PlanResources& r;
  std::size_t local;
  std::vector<std::vector<std::vector<PreparedLaunch>>> launches;  // per memory, per task
  std::vector<QueuedStep> steps;
  std::size_t devices_used = 1;
  // Devices with memories of their own: the copies between them, and what
  // each device's first step of the next substep waits for.
  std::unique_ptr<MemoryCopies> copies;
  std::vector<std::vector<cl_event>> barrier;
  std::size_t bytes_moved = 0;  // by the last enqueue()

  // Recording: first-launch start and last-launch end events per task.
  EventList record_start, record_end;
  bool have_record = false;
  // Each queue's last event of the previous substep (the barrier between substeps).
  EventList last_on_device;
  // Events no longer needed, released only once every queue is finished:
  // releasing an event that another device's queue still waits on crashed
  // pocl 3.1's pthread driver now and then (use after free in its worker).
  std::vector<cl_event> graveyard;

  Impl(const PlanResources& resources, std::size_t local_size) : r(resources), local(local_size) {
    launches.resize(r.set.contexts.size());
    for (std::size_t m = 0; m < launches.size(); ++m) {
      launches[m].resize(r.plan.graph.size());
      for (sched::TaskId id = 0; id < r.plan.graph.size(); ++id) {
        for (const plan::KernelLaunch& launch : r.plan.launches.at(id)) {
          if (launch.range.count > 0) launches[m][id].push_back(prepare(launch, m));
        }
      }
    }
    last_on_device.resize(r.set.devices.size());
  }

  PreparedLaunch prepare(const plan::KernelLaunch& launch, std::size_t memory) {
    cl_int err = CL_SUCCESS;
    const std::string name = "ats_k_" + launch.function;
    cl::Kernel kernel(r.programs.at(memory), name.c_str(), &err);
    check_cl(err, fmt::format("creating kernel '{}'", name).c_str());
    cl_uint i = 0;
    for (const plan::KernelArg& a : launch.args) {
      cl_int rc = CL_SUCCESS;
      switch (a.kind) {
        case plan::KernelArg::Kind::buffer:
          rc = clSetKernelArgSVMPointer(kernel(), i, r.buffers.at(memory).at(a.buffer));
          break;
        case plan::KernelArg::Kind::i32:
          rc = clSetKernelArg(kernel(), i, sizeof(cl_int), &a.i32);
          break;
        case plan::KernelArg::Kind::f32:
          rc = clSetKernelArg(kernel(), i, sizeof(cl_float), &a.f32);
          break;
      }
      check_cl(rc, fmt::format("setting argument {} of kernel '{}'", i, name).c_str());
      ++i;
    }
    const cl_int first = launch.range.first, count = launch.range.count;
    check_cl(clSetKernelArg(kernel(), i, sizeof(cl_int), &first), "setting a kernel's range");
    check_cl(clSetKernelArg(kernel(), i + 1, sizeof(cl_int), &count), "setting a kernel's range");
    const auto n = static_cast<std::size_t>(count);
    return {kernel, (n + local - 1) / local * local};
  }

  void set_steps(const std::vector<Step>& new_steps) {
    finish_all();
    last_on_device.clear();
    steps.clear();
    for (const Step& s : new_steps) steps.push_back({s.task, s.device, s.waits, false, false});
    std::vector<std::size_t> position(r.plan.graph.size(), 0);
    for (std::size_t i = 0; i < steps.size(); ++i) position[steps[i].task] = i;
    for (const QueuedStep& s : steps) {
      for (sched::TaskId producer : s.waits) steps[position[producer]].event_needed = true;
    }
    std::vector<char> seen(r.set.devices.size(), 0);
    devices_used = 0;
    for (QueuedStep& s : steps) {
      s.first_on_device = !seen[s.device];
      if (!seen[s.device]) ++devices_used;
      seen[s.device] = 1;
    }
    copies.reset();
    barrier.assign(r.set.devices.size(), {});
    if (!r.set.one_memory()) {
      // Every dependency between devices goes through MemoryCopies.
      for (QueuedStep& s : steps) s.event_needed = false;
      copies = std::make_unique<MemoryCopies>(r, new_steps);
      return;
    }
    // With several queues, each queue's last task ends the substep for the others.
    if (devices_used > 1) {
      std::vector<char> last(r.set.devices.size(), 0);
      for (auto it = steps.rbegin(); it != steps.rend(); ++it) {
        if (!last[it->device]) it->event_needed = true;
        last[it->device] = 1;
      }
    }
  }

  // Devices with memories of their own: kernels in step order, the copies
  // MemoryCopies plans around them, and its barrier between substeps.
  void enqueue_substep_separate(bool record) {
    const auto& graph = r.plan.graph;
    EventList starts, ends;
    if (record) {
      starts.resize(graph.size());
      ends.resize(graph.size());
      copies->record_next_substep();
    }
    std::vector<cl_event> wait;
    std::vector<char> started(r.set.devices.size(), 0);
    for (std::size_t k = 0; k < steps.size(); ++k) {
      const QueuedStep& step = steps[k];
      wait.clear();
      if (!started[step.device]) {
        wait = barrier[step.device];
        started[step.device] = 1;
      }
      copies->before_step(k, wait);
      const cl::CommandQueue& queue = r.set.queues[step.device];
      const auto& task_launches = launches[r.set.memory_of[step.device]][step.task];
      if (task_launches.empty() || record) {
        cl_event marker = nullptr;
        check_cl(clEnqueueMarkerWithWaitList(queue(), static_cast<cl_uint>(wait.size()),
                                             wait.empty() ? nullptr : wait.data(), record ? &marker : nullptr),
                 "enqueueing a marker");
        wait.clear();
        if (record) starts[step.task] = marker;
      }
      for (std::size_t l = 0; l < task_launches.size(); ++l) {
        cl_event produced = nullptr;
        const bool last = l + 1 == task_launches.size();
        check_cl(clEnqueueNDRangeKernel(queue(), task_launches[l].kernel(), 1, nullptr, &task_launches[l].global,
                                        &local, static_cast<cl_uint>(wait.size()), wait.empty() ? nullptr : wait.data(),
                                        record && last ? &produced : nullptr),
                 "enqueueing a kernel");
        wait.clear();
        if (record && last) ends[step.task] = produced;
      }
      if (record && ends[step.task] == nullptr) {
        cl_event marker = nullptr;
        check_cl(clEnqueueMarkerWithWaitList(queue(), 0, nullptr, &marker), "enqueueing a marker");
        ends[step.task] = marker;
      }
      copies->after_step(k);
    }
    barrier = copies->end_substep();
    bytes_moved += copies->take_bytes();
    if (record) {
      record_start.swap(starts);
      record_end.swap(ends);
      have_record = true;
    }
    starts.retire_into(graveyard);
    ends.retire_into(graveyard);
  }

  void enqueue_substep(bool record) {
    if (copies) {
      enqueue_substep_separate(record);
      return;
    }
    const auto& graph = r.plan.graph;
    EventList events;
    events.resize(graph.size());
    EventList starts;
    if (record) starts.resize(graph.size());
    EventList this_last;
    this_last.resize(r.set.devices.size());
    std::vector<cl_event> wait_list;
    for (const QueuedStep& step : steps) {
      wait_list.clear();
      for (sched::TaskId producer : step.waits) {
        if (events[producer] == nullptr) {
          throw internal_error(fmt::format("executor: task '{}' waits for '{}', which has not been enqueued before it",
                                           graph.task(step.task).name, graph.task(producer).name));
        }
        wait_list.push_back(events[producer]);
      }
      if (step.first_on_device && devices_used > 1) {
        for (std::size_t d = 0; d < r.set.devices.size(); ++d) {
          if (d != step.device && last_on_device[d] != nullptr) wait_list.push_back(last_on_device[d]);
        }
      }
      const cl::CommandQueue& queue = r.set.queues[step.device];
      const auto& task_launches = launches[0][step.task];
      const bool want_event = step.event_needed || record;
      if (task_launches.empty()) {
        // Nothing to run: a marker keeps the ordering (and the timing) of the graph.
        cl_event marker = nullptr;
        check_cl(
            clEnqueueMarkerWithWaitList(queue(), static_cast<cl_uint>(wait_list.size()),
                                        wait_list.empty() ? nullptr : wait_list.data(), want_event ? &marker : nullptr),
            "enqueueing a marker");
        if (want_event) events[step.task] = marker;
        if (record) {
          clRetainEvent(marker);
          starts[step.task] = marker;
        }
      }
      for (std::size_t k = 0; k < task_launches.size(); ++k) {
        const bool first = k == 0, last = k + 1 == task_launches.size();
        cl_event produced = nullptr;
        const bool produce = (last && want_event) || (first && record);
        check_cl(clEnqueueNDRangeKernel(queue(), task_launches[k].kernel(), 1, nullptr, &task_launches[k].global,
                                        &local, first ? static_cast<cl_uint>(wait_list.size()) : 0,
                                        first && !wait_list.empty() ? wait_list.data() : nullptr,
                                        produce ? &produced : nullptr),
                 "enqueueing a kernel");
        if (first && record) {
          starts[step.task] = produced;
          if (last) clRetainEvent(produced);
        }
        if (last && want_event) events[step.task] = produced;
      }
      if (step.event_needed && events[step.task] != nullptr) {
        if (this_last[step.device] != nullptr) graveyard.push_back(this_last[step.device]);
        this_last[step.device] = events[step.task];
        clRetainEvent(events[step.task]);
      }
    }
    for (const cl::CommandQueue& q : r.set.queues) check_cl(clFlush(q()), "flushing a queue");
    last_on_device.swap(this_last);
    this_last.retire_into(graveyard);
    if (record) {
      record_start.swap(starts);
      record_end.swap(events);
      have_record = true;
    }
    starts.retire_into(graveyard);
    events.retire_into(graveyard);
  }

  void finish_all() {
    for (const cl::CommandQueue& q : r.set.queues) check_cl(clFinish(q()), "waiting for a device");
    for (cl_event e : graveyard) clReleaseEvent(e);
    graveyard.clear();
    if (copies) {
      for (cl_event e : copies->graveyard()) clReleaseEvent(e);
      copies->graveyard().clear();
    }
    // The barrier's events were among them; every queue is finished, so
    // the next substep has nothing to wait for.
    barrier.assign(r.set.devices.size(), {});
  }

  std::vector<sched::TaskTiming> timings() {
    if (!have_record) throw internal_error("executor: no substep was recorded");
    finish_all();
    std::vector<sched::TaskTiming> out;
    double origin = std::numeric_limits<double>::infinity();
    for (const QueuedStep& s : steps) {
      if (record_start[s.task] == nullptr) continue;
      const double start = event_ns(record_start[s.task], CL_PROFILING_COMMAND_START);
      const double end = event_ns(record_end[s.task], CL_PROFILING_COMMAND_END);
      origin = std::min(origin, start);
      out.push_back({s.task, static_cast<sched::DeviceId>(s.device), start, end});
    }
    for (sched::TaskTiming& t : out) {
      t.start_ms = (t.start_ms - origin) * 1e-6;
      t.finish_ms = (t.finish_ms - origin) * 1e-6;
    }
    return out;
  }

  // Median over `repetitions` of `hop(a, b)`: start of b minus end of a, in
  // ms (two devices of one memory, or one device's queue).
  double probe_hops(std::size_t from, std::size_t to, int repetitions, bool same_queue) {
    const std::size_t memory = r.set.memory_of[from];
    const cl::Program probe =
        build_program(r.set.contexts[memory], r.set.devices_of(memory), "noop", language_option(r.set));
    cl::Kernel noop(probe, "probe_noop");
    check_cl(clSetKernelArgSVMPointer(noop(), 0, r.buffers[memory].empty() ? nullptr : r.buffers[memory].front()),
             "setting the probe's argument");
    finish_all();
    std::vector<double> hops;
    const std::size_t one = 1;
    const cl::CommandQueue& qa = r.set.queues[from];
    const cl::CommandQueue& qb = r.set.queues[same_queue ? from : to];
    for (int rep = 0; rep <= repetitions; ++rep) {
      cl_event a = nullptr, b = nullptr;
      check_cl(clEnqueueNDRangeKernel(qa(), noop(), 1, nullptr, &one, &one, 0, nullptr, &a), "enqueueing the probe");
      check_cl(clEnqueueNDRangeKernel(qb(), noop(), 1, nullptr, &one, &one, 1, &a, &b), "enqueueing the probe");
      check_cl(clFinish(qb()), "waiting for the probe");
      if (rep > 0) {
        const double gap = same_queue ? event_ns(b, CL_PROFILING_COMMAND_END) - event_ns(a, CL_PROFILING_COMMAND_END)
                                      : event_ns(b, CL_PROFILING_COMMAND_START) - event_ns(a, CL_PROFILING_COMMAND_END);
        hops.push_back(gap * 1e-6);
      }
      clReleaseEvent(a);
      clReleaseEvent(b);
    }
    std::nth_element(hops.begin(), hops.begin() + hops.size() / 2, hops.end());
    return std::max(hops[hops.size() / 2], 0.0);
  }
};

EventRunner::EventRunner(const PlanResources& resources, std::size_t local_size)
    : impl_(std::make_unique<Impl>(resources, local_size)) {}

EventRunner::~EventRunner() {
  if (impl_) {
    for (const cl::CommandQueue& q : impl_->r.set.queues) clFinish(q());
    for (cl_event e : impl_->graveyard) clReleaseEvent(e);
  }
}

void EventRunner::set_steps(const std::vector<Step>& steps) { impl_->set_steps(steps); }

void EventRunner::enqueue(int count, bool record) {
  for (int s = 0; s < count; ++s) impl_->enqueue_substep(record && s + 1 == count);
}

std::vector<sched::TaskTiming> EventRunner::timings() { return impl_->timings(); }

void EventRunner::finish() { impl_->finish_all(); }

double EventRunner::latency_ms(std::size_t from, std::size_t to, int repetitions) {
  if (impl_->r.set.memory_of[from] != impl_->r.set.memory_of[to]) {
    impl_->finish_all();
    return measure_link(impl_->r, from, to, repetitions).latency_ms;
  }
  return impl_->probe_hops(from, to, repetitions, false);
}

std::size_t EventRunner::take_bytes_moved() {
  const std::size_t b = impl_->bytes_moved;
  impl_->bytes_moved = 0;
  return b;
}

std::vector<sched::CopyTiming> EventRunner::copies() {
  impl_->finish_all();
  return impl_->copies ? impl_->copies->recorded() : std::vector<sched::CopyTiming>{};
}

const plan::TransferPlan* EventRunner::transfer_plan() const {
  return impl_->copies ? &impl_->copies->transfers() : nullptr;
}

double EventRunner::launch_gap_ms(std::size_t device, int repetitions) {
  return impl_->probe_hops(device, device, repetitions, true);
}

}  // namespace atssim::device
