#include "device/plan_executor.hpp"

#include <algorithm>
#include <limits>

#include <fmt/format.h>

#include "device/device_set_impl.hpp"
#include "device/program_builder.hpp"
#include "device/svm_arena.hpp"
#include "sched/cost_refit.hpp"
#include "util/error.hpp"

namespace atssim::device {

namespace {

struct PreparedLaunch {
  cl::Kernel kernel;
  std::size_t global = 0;
};

// One task to enqueue: where, and which tasks of this substep it waits for.
struct Step {
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
  std::size_t size() const { return events_.size(); }
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

struct PlanExecutor::Impl {
  const DeviceSet::Impl& set;
  const solver::SubstepPlan& plan;
  ExecutorOptions options;
  SvmArena arena;
  std::vector<void*> buffers;
  std::vector<std::size_t> sizes;
  std::vector<std::vector<PreparedLaunch>> launches;  // per task
  std::vector<sched::TaskId> topological;
  std::vector<Step> steps;
  std::size_t devices_used = 1;

  // Recording: first-launch start and last-launch end events per task.
  EventList record_start, record_end;
  bool have_record = false;
  // Each queue's last event of the previous substep (the barrier between substeps).
  EventList last_on_device;
  // Events no longer needed, released only once every queue is finished:
  // releasing an event that another device's queue still waits on crashed
  // pocl 3.1's pthread driver now and then (use after free in its worker).
  std::vector<cl_event> graveyard;

  Impl(const DeviceSet& devices, const solver::SubstepPlan& p, ExecutorOptions o)
      : set(devices.impl()),
        plan(p),
        options(o),
        arena(devices.impl().context, o.svm == SvmMode::fine ||
                                          (o.svm == SvmMode::automatic && devices.fine_grain_svm())) {
    if (options.device >= set.devices.size()) {
      throw Error(fmt::format("executor: device {} is not in the set of {}", options.device, set.devices.size()));
    }
    if (arena.fine_grain() && !devices.fine_grain_svm()) {
      throw input_error("fine-grain SVM was asked for but a device does not offer it; use --svm coarse");
    }
    for (const auto& spec : plan.buffers) {
      void* ptr = arena.allocate(spec.initial.size());
      arena.write(set.queues[options.device], ptr, spec.initial.data(), spec.initial.size());
      buffers.push_back(ptr);
      sizes.push_back(spec.initial.size());
    }
    const cl::Program program = build_program(set.context, set.devices, plan.program);
    launches.resize(plan.graph.size());
    for (sched::TaskId id = 0; id < plan.graph.size(); ++id) {
      for (const solver::KernelLaunch& launch : plan.launches.at(id)) {
        if (launch.global_size > 0) launches[id].push_back(prepare(program, launch));
      }
    }
    topological = plan.graph.topological_order();
    last_on_device.resize(set.devices.size());
  }

  PreparedLaunch prepare(const cl::Program& program, const solver::KernelLaunch& launch) {
    cl_int err = CL_SUCCESS;
    cl::Kernel kernel(program, launch.kernel.c_str(), &err);
    check_cl(err, fmt::format("creating kernel '{}'", launch.kernel).c_str());
    for (cl_uint i = 0; i < launch.args.size(); ++i) {
      const solver::KernelArg& a = launch.args[i];
      cl_int rc = CL_SUCCESS;
      switch (a.kind) {
        case solver::KernelArg::Kind::buffer:
          rc = clSetKernelArgSVMPointer(kernel(), i, buffers.at(a.buffer));
          break;
        case solver::KernelArg::Kind::i32:
          rc = clSetKernelArg(kernel(), i, sizeof(cl_int), &a.i32);
          break;
        case solver::KernelArg::Kind::f32:
          rc = clSetKernelArg(kernel(), i, sizeof(cl_float), &a.f32);
          break;
      }
      check_cl(rc, fmt::format("setting argument {} of kernel '{}'", i, launch.kernel).c_str());
    }
    const std::size_t local = options.local_size;
    return {kernel, (launch.global_size + local - 1) / local * local};
  }

  void set_steps(std::vector<Step> new_steps) {
    finish_all();
    last_on_device.clear();
    steps = std::move(new_steps);
    std::vector<char> seen(set.devices.size(), 0);
    devices_used = 0;
    for (Step& s : steps) {
      s.first_on_device = !seen[s.device];
      if (!seen[s.device]) ++devices_used;
      seen[s.device] = 1;
    }
    // With several queues, each queue's last task ends the substep for the others.
    if (devices_used > 1) {
      std::vector<char> last(set.devices.size(), 0);
      for (auto it = steps.rbegin(); it != steps.rend(); ++it) {
        if (!last[it->device]) it->event_needed = true;
        last[it->device] = 1;
      }
    }
  }

  void enqueue_substep(bool record) {
    EventList events;
    events.resize(plan.graph.size());
    EventList starts;
    if (record) starts.resize(plan.graph.size());
    EventList this_last;
    this_last.resize(set.devices.size());
    std::vector<cl_event> wait_list;
    const std::size_t local = options.local_size;
    for (const Step& step : steps) {
      wait_list.clear();
      for (sched::TaskId producer : step.waits) {
        if (events[producer] == nullptr) {
          throw Error(fmt::format("executor: task '{}' waits for '{}', which has not been enqueued before it",
                                  plan.graph.task(step.task).name, plan.graph.task(producer).name));
        }
        wait_list.push_back(events[producer]);
      }
      if (step.first_on_device && devices_used > 1) {
        for (std::size_t d = 0; d < set.devices.size(); ++d) {
          if (d != step.device && last_on_device[d] != nullptr) wait_list.push_back(last_on_device[d]);
        }
      }
      const cl::CommandQueue& queue = set.queues[step.device];
      const auto& task_launches = launches[step.task];
      const bool want_event = step.event_needed || record;
      if (task_launches.empty()) {
        // Nothing to run: a marker keeps the ordering (and the timing) of the graph.
        cl_event marker = nullptr;
        check_cl(clEnqueueMarkerWithWaitList(queue(), static_cast<cl_uint>(wait_list.size()),
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
    for (const cl::CommandQueue& q : set.queues) check_cl(clFlush(q()), "flushing a queue");
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
    for (const cl::CommandQueue& q : set.queues) check_cl(clFinish(q()), "waiting for a device");
    for (cl_event e : graveyard) clReleaseEvent(e);
    graveyard.clear();
  }

  std::vector<TaskTiming> timings() {
    if (!have_record) throw Error("executor: no substep was recorded");
    finish_all();
    std::vector<TaskTiming> out;
    double origin = std::numeric_limits<double>::infinity();
    for (const Step& s : steps) {
      if (record_start[s.task] == nullptr) continue;
      const double start = event_ns(record_start[s.task], CL_PROFILING_COMMAND_START);
      const double end = event_ns(record_end[s.task], CL_PROFILING_COMMAND_END);
      origin = std::min(origin, start);
      out.push_back({s.task, s.device, start, end});
    }
    for (TaskTiming& t : out) {
      t.start_ms = (t.start_ms - origin) * 1e-6;
      t.finish_ms = (t.finish_ms - origin) * 1e-6;
    }
    return out;
  }
};

PlanExecutor::PlanExecutor(const DeviceSet& devices, const solver::SubstepPlan& plan, ExecutorOptions options)
    : impl_(std::make_unique<Impl>(devices, plan, options)) {
  run_on(options.device);
}

PlanExecutor::~PlanExecutor() {
  if (impl_) {
    for (const cl::CommandQueue& q : impl_->set.queues) clFinish(q());
    for (cl_event e : impl_->graveyard) clReleaseEvent(e);
  }
}

std::size_t PlanExecutor::device_count() const { return impl_->set.devices.size(); }

void PlanExecutor::run_on(std::size_t device) {
  if (device >= device_count()) throw Error(fmt::format("executor: no device {}", device));
  std::vector<Step> steps;
  for (sched::TaskId t : impl_->topological) steps.push_back({t, device, {}, false, false});
  impl_->set_steps(std::move(steps));
}

void PlanExecutor::run_schedule(const sched::Schedule& schedule, std::span<const sched::Wait> waits) {
  const auto& graph = impl_->plan.graph;
  if (schedule.task_count() != graph.size() || schedule.devices.size() > device_count()) {
    throw Error(fmt::format("executor: a schedule of {} tasks on {} devices does not fit a plan of {} tasks on {}",
                            schedule.task_count(), schedule.devices.size(), graph.size(), device_count()));
  }
  // Enqueue in order of predicted start, so a producer is always enqueued
  // before a consumer that waits for it (its start is at least the
  // producer's finish).
  std::vector<Step> steps;
  for (std::size_t d = 0; d < schedule.devices.size(); ++d) {
    for (const sched::Slot& slot : schedule.devices[d]) steps.push_back({slot.task, d, {}, false, false});
  }
  std::vector<std::size_t> topo_index(graph.size());
  for (std::size_t i = 0; i < impl_->topological.size(); ++i) topo_index[impl_->topological[i]] = i;
  std::stable_sort(steps.begin(), steps.end(), [&](const Step& a, const Step& b) {
    const double sa = schedule.slot(a.task).start_ms, sb = schedule.slot(b.task).start_ms;
    if (sa != sb) return sa < sb;
    return topo_index[a.task] < topo_index[b.task];
  });
  std::vector<std::size_t> position(graph.size());
  for (std::size_t i = 0; i < steps.size(); ++i) position[steps[i].task] = i;
  for (const sched::Wait& w : waits) {
    steps[position[w.consumer]].waits.push_back(w.producer);
    steps[position[w.producer]].event_needed = true;
  }
  impl_->set_steps(std::move(steps));
}

void PlanExecutor::enqueue_substeps(int count, bool record) {
  for (int s = 0; s < count; ++s) impl_->enqueue_substep(record && s + 1 == count);
}

std::vector<TaskTiming> PlanExecutor::recorded() { return impl_->timings(); }

sched::CostTable PlanExecutor::profile(int repetitions) {
  const std::size_t tasks = impl_->plan.graph.size();
  std::vector<std::vector<std::byte>> snapshot;
  for (std::size_t b = 0; b < impl_->buffers.size(); ++b) snapshot.push_back(read(static_cast<solver::BufferId>(b)));
  const std::vector<Step> kept = impl_->steps;

  sched::CostTable costs(tasks, device_count());
  for (std::size_t d = 0; d < device_count(); ++d) {
    run_on(d);
    std::vector<std::vector<double>> samples(tasks);
    for (int r = 0; r <= repetitions; ++r) {
      enqueue_substeps(1, true);
      const auto timings = recorded();
      if (r == 0) continue;  // warm-up: first launches may compile
      // In one in-order stream a task costs from the end of the one before it
      // to its own end: the launch gap is part of what it costs the queue.
      double previous_end = timings.empty() ? 0.0 : timings.front().start_ms;
      for (const TaskTiming& t : timings) {
        samples[t.task].push_back(std::max(t.finish_ms - previous_end, 1e-6));
        previous_end = t.finish_ms;
      }
    }
    for (std::size_t t = 0; t < tasks; ++t) {
      costs.at(static_cast<sched::TaskId>(t), static_cast<sched::DeviceId>(d)) =
          samples[t].empty() ? 1e-6 : sched::trimmed_mean(samples[t], 0.2);
    }
  }
  for (std::size_t b = 0; b < snapshot.size(); ++b) write(static_cast<solver::BufferId>(b), snapshot[b]);
  impl_->set_steps(kept);
  return costs;
}

double PlanExecutor::measure_latency_ms(std::size_t from, std::size_t to, int repetitions) {
  auto& impl = *impl_;
  const cl::Program probe = build_program(impl.set.context, impl.set.devices, "probe");
  cl::Kernel noop(probe, "probe_noop");
  check_cl(clSetKernelArgSVMPointer(noop(), 0, impl.buffers.empty() ? nullptr : impl.buffers.front()),
           "setting the probe's argument");
  finish();
  std::vector<double> hops;
  const std::size_t one = 1;
  for (int r = 0; r <= repetitions; ++r) {
    cl_event a = nullptr, b = nullptr;
    check_cl(clEnqueueNDRangeKernel(impl.set.queues[from](), noop(), 1, nullptr, &one, &one, 0, nullptr, &a),
             "enqueueing the probe");
    check_cl(clEnqueueNDRangeKernel(impl.set.queues[to](), noop(), 1, nullptr, &one, &one, 1, &a, &b),
             "enqueueing the probe");
    check_cl(clFinish(impl.set.queues[to]()), "waiting for the probe");
    if (r > 0) hops.push_back((event_ns(b, CL_PROFILING_COMMAND_START) - event_ns(a, CL_PROFILING_COMMAND_END)) * 1e-6);
    clReleaseEvent(a);
    clReleaseEvent(b);
  }
  std::nth_element(hops.begin(), hops.begin() + hops.size() / 2, hops.end());
  return std::max(hops[hops.size() / 2], 0.0);
}

void PlanExecutor::finish() { impl_->finish_all(); }

std::vector<std::byte> PlanExecutor::read(solver::BufferId id) {
  finish();
  std::vector<std::byte> out(impl_->sizes.at(id));
  impl_->arena.read(impl_->set.queues[impl_->options.device], impl_->buffers.at(id), out.data(), out.size());
  return out;
}

void PlanExecutor::write(solver::BufferId id, std::span<const std::byte> bytes) {
  finish();
  if (bytes.size() != impl_->sizes.at(id)) throw Error("executor: write of the wrong size");
  impl_->arena.write(impl_->set.queues[impl_->options.device], impl_->buffers.at(id), bytes.data(), bytes.size());
}

void PlanExecutor::read_positions(std::vector<float>& xyz) {
  const std::vector<std::byte> raw = read(impl_->plan.positions);
  const auto* p = reinterpret_cast<const float*>(raw.data());
  const std::size_t n = raw.size() / (4 * sizeof(float));
  xyz.resize(3 * n);
  for (std::size_t i = 0; i < n; ++i) {
    xyz[3 * i] = p[4 * i];
    xyz[3 * i + 1] = p[4 * i + 1];
    xyz[3 * i + 2] = p[4 * i + 2];
  }
}

bool PlanExecutor::fine_grain() const { return impl_->arena.fine_grain(); }

}  // namespace atssim::device
