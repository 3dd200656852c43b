#include "device/fused_runner.hpp"

#include <algorithm>
#include <atomic>
#include <chrono>
#include <condition_variable>
#include <cstring>
#include <limits>
#include <map>
#include <mutex>
#include <string>

#include <fmt/format.h>

#include "device/cycle_clock.hpp"
#include "device/dispatch_types.h"
#include "device/program_builder.hpp"
#include "util/error.hpp"

namespace atssim::device {

namespace {

// The counters count launches; reset them long before an int overflows.
constexpr long long kEpochLimit = 1 << 22;

int load(int* p) { return std::atomic_ref<int>(*p).load(std::memory_order_acquire); }
void store(int* p, int v) { std::atomic_ref<int>(*p).store(v, std::memory_order_release); }

// Counts launches still running; the OpenCL runtime calls on_complete.
struct Completion {
  std::mutex mutex;
  std::condition_variable changed;
  int pending = 0;
};

// Notifies under the lock: once a waiter sees pending == 0 with the lock
// held, no callback touches the Completion any more.
void CL_CALLBACK on_complete(cl_event, cl_int, void* user) {
  auto* c = static_cast<Completion*>(user);
  const std::lock_guard<std::mutex> lock(c->mutex);
  --c->pending;
  c->changed.notify_all();
}

// Waits until every callback of `events` has run.
void drain(std::vector<cl_event>& events, Completion& completion) {
  if (!events.empty()) clWaitForEvents(static_cast<cl_uint>(events.size()), events.data());
  std::unique_lock<std::mutex> lock(completion.mutex);
  completion.changed.wait(lock, [&] { return completion.pending == 0; });
}

std::uint64_t word_of(const plan::KernelArg& a, const std::vector<void*>& buffers) {
  switch (a.kind) {
    case plan::KernelArg::Kind::buffer:
      return reinterpret_cast<std::uintptr_t>(buffers.at(a.buffer));
    case plan::KernelArg::Kind::i32:
      return static_cast<std::uint32_t>(a.i32);
    case plan::KernelArg::Kind::f32: {
      std::uint32_t bits = 0;
      std::memcpy(&bits, &a.f32, sizeof bits);
      return bits;
    }
  }
  return 0;
}

// A sanitizer build (ATSSIM_SANITIZE: ASan + UBSan) runs the host several
// times slower, and on a loaded machine a device's spinning work-groups lose
// whole time slices: a watched wait there gives up only after
// ATSSIM_WAIT_SCALE (10, set by lib/device/CMakeLists.txt) times its limit,
// so that a slow run is not reported as a stalled one. 1 elsewhere.
#ifdef ATSSIM_WAIT_SCALE
constexpr double wait_scale = ATSSIM_WAIT_SCALE;
#else
constexpr double wait_scale = 1.0;
#endif

// The limit as the error states it: "0.3 s", or under a sanitizer build
// "0.3 s (3 s: this sanitizer build waits 10 times as long)".
std::string limit_text(double timeout_s) {
  if (wait_scale == 1.0) return fmt::format("{:g} s", timeout_s);
  return fmt::format("{:g} s ({:g} s: this sanitizer build waits {:g} times as long)", timeout_s,
                     timeout_s * wait_scale, wait_scale);
}

// Waits for `events` like finish() does, giving up after `timeout_s`
// (times wait_scale) without a change of `progress()`; returns false when
// it gave up (the abort flag is then set and every event has completed).
template <typename Progress>
bool wait_watched(std::vector<cl_event>& events, Completion& completion, int* abort_flag, double timeout_s,
                  Progress progress) {
  timeout_s *= wait_scale;
  bool gave_up = false;
  {
    std::unique_lock<std::mutex> lock(completion.mutex);
    long long seen = progress();
    double last_change = host_ms();
    while (completion.pending > 0) {
      completion.changed.wait_for(lock, std::chrono::milliseconds(50));
      if (completion.pending == 0) break;
      const long long now = progress();
      if (now != seen) {
        seen = now;
        last_change = host_ms();
      } else if (host_ms() - last_change > 1000.0 * timeout_s) {
        store(abort_flag, 1);
        gave_up = true;
        break;
      }
    }
  }
  drain(events, completion);
  return !gave_up;
}

}  // namespace

struct FusedRunner::Impl {
  const PlanResources& r;
  SvmArena& arena;
  FusedOptions options;
  cl::Program program;
  std::vector<CycleClock> clocks;  // empty: no task clock
  std::vector<int> groups;         // work-groups per device (its compute units)
  int stamp_stride = 1;            // the most groups of any device

  // SVM shared with the running dispatchers.
  int* counters = nullptr;  // ATS_LINE ints per task
  int* control = nullptr;   // ATS_CONTROL_INTS(devices)
  cl_ulong* stamps = nullptr;

  // The current schedule, per device.
  struct DeviceTables {
    std::vector<ats_slot> slots;
    std::vector<ats_launch> launches;
    std::vector<ats_wait> waits;
    std::vector<std::uint64_t> args;
    void* svm_slots = nullptr;
    void* svm_launches = nullptr;
    void* svm_waits = nullptr;
    void* svm_args = nullptr;
    std::vector<sched::TaskId> tasks;  // in slot order
    cl::Kernel kernel;
  };
  std::vector<DeviceTables> tables;
  std::vector<std::size_t> device_of;  // per task
  long long epoch = 0;                 // substeps run since the counters were reset

  Completion completion;
  std::vector<cl_event> in_flight;  // one per launching device
  std::vector<sched::DeviceId> in_flight_device;
  std::vector<sched::LaunchTiming> last_launches;
  int last_substeps = 0;
  bool have_record = false;
  bool broken = false;

  Impl(const PlanResources& resources, SvmArena& a, const FusedOptions& o) : r(resources), arena(a), options(o) {
    if (options.task_clock) clocks = cycle_clocks(r.set, arena);
    for (const DeviceInfo& info : r.set.infos) groups.push_back(std::max(1, info.compute_units));
    stamp_stride = *std::max_element(groups.begin(), groups.end());
    const std::size_t tasks = std::max<std::size_t>(r.plan.graph.size(), 1);
    counters = static_cast<int*>(arena.allocate(tasks * ATS_LINE * sizeof(int)));
    control = static_cast<int*>(arena.allocate(ATS_CONTROL_INTS(r.set.devices.size()) * sizeof(int)));
    stamps = static_cast<cl_ulong*>(arena.allocate(tasks * stamp_stride * 2 * sizeof(cl_ulong)));
    tables.resize(r.set.devices.size());
    for (DeviceTables& t : tables) {
      cl_int err = CL_SUCCESS;
      t.kernel = cl::Kernel(r.programs.at(0), "ats_dispatch", &err);
      check_cl(err, fmt::format("creating the dispatcher of program '{}'", r.plan.program).c_str());
      // The task functions reach the plan's buffers through pointers in the
      // argument words, not through kernel arguments.
      if (!r.buffers.at(0).empty()) {
        check_cl(clSetKernelExecInfo(t.kernel(), CL_KERNEL_EXEC_INFO_SVM_PTRS, r.buffers[0].size() * sizeof(void*),
                                     r.buffers[0].data()),
                 "declaring the plan's buffers to the dispatcher");
      }
    }
  }

  ~Impl() {
    wait_quietly();
    for (DeviceTables& t : tables) release_tables(t);
    arena.release(counters);
    arena.release(control);
    arena.release(stamps);
  }

  void wait_quietly() {
    if (in_flight.empty()) return;
    store(control, 1);  // nothing waits for the result: let every spin end
    drain(in_flight, completion);
    for (cl_event e : in_flight) clReleaseEvent(e);
    in_flight.clear();
  }

  void release_tables(DeviceTables& t) {
    for (void* p : {t.svm_slots, t.svm_launches, t.svm_waits, t.svm_args}) {
      if (p != nullptr) arena.release(p);
    }
    t.svm_slots = t.svm_launches = t.svm_waits = t.svm_args = nullptr;
  }

  template <typename T>
  void* upload(const std::vector<T>& values) {
    void* p = arena.allocate(std::max<std::size_t>(values.size() * sizeof(T), sizeof(T)));
    if (!values.empty()) std::memcpy(p, values.data(), values.size() * sizeof(T));
    return p;
  }

  int launch_count(sched::TaskId t) const { return std::max<int>(1, static_cast<int>(r.plan.launches[t].size())); }
  int units(sched::TaskId t) const { return groups[device_of[t]] * launch_count(t); }

  void reset_counters() {
    std::memset(counters, 0, std::max<std::size_t>(r.plan.graph.size(), 1) * ATS_LINE * sizeof(int));
    std::memset(control, 0, ATS_CONTROL_INTS(r.set.devices.size()) * sizeof(int));
    epoch = 0;
  }

  void set_steps(const std::vector<Step>& steps) {
    finish();
    const std::size_t n = r.set.devices.size();
    device_of.assign(r.plan.graph.size(), 0);
    for (DeviceTables& t : tables) {
      release_tables(t);
      t.slots.clear();
      t.launches.clear();
      t.waits.clear();
      t.args.clear();
      t.tasks.clear();
    }
    for (const Step& s : steps) {
      device_of[s.task] = s.device;
      tables[s.device].tasks.push_back(s.task);
    }
    std::size_t devices_used = 0;
    for (const DeviceTables& t : tables) devices_used += t.tasks.empty() ? 0 : 1;
    for (std::size_t d = 0; d < n; ++d) {
      DeviceTables& t = tables[d];
      for (std::size_t k = 0; k < t.tasks.size(); ++k) {
        const sched::TaskId task = t.tasks[k];
        const Step& step = *std::find_if(steps.begin(), steps.end(), [&](const Step& s) { return s.task == task; });
        ats_slot slot{};
        slot.task = static_cast<int>(task);
        slot.first_wait = static_cast<int>(t.waits.size());
        // In order on this device, as an in-order queue runs it: with one
        // work-group that is program order; with several, a wait for all of
        // them on the task before (of this substep, or the last of the one before).
        if (groups[d] > 1) {
          const sched::TaskId before = k > 0 ? t.tasks[k - 1] : t.tasks.back();
          t.waits.push_back({static_cast<int>(before), units(before), k > 0 ? 0 : -1, 0});
        }
        for (sched::TaskId producer : step.waits)
          t.waits.push_back({static_cast<int>(producer), units(producer), 0, 0});
        // A substep starts when every other device has ended the one before.
        if (k == 0 && devices_used > 1) {
          for (std::size_t o = 0; o < n; ++o) {
            if (o == d || tables[o].tasks.empty()) continue;
            const sched::TaskId last = tables[o].tasks.back();
            t.waits.push_back({static_cast<int>(last), units(last), -1, 0});
          }
        }
        slot.wait_count = static_cast<int>(t.waits.size()) - slot.first_wait;
        slot.first_launch = static_cast<int>(t.launches.size());
        const auto& task_launches = r.plan.launches[task];
        for (std::size_t l = 0; l < task_launches.size(); ++l) {
          const plan::KernelLaunch& launch = task_launches[l];
          t.launches.push_back(
              {r.functions[task][l], launch.range.first, launch.range.count, static_cast<int>(t.args.size())});
          for (const plan::KernelArg& a : launch.args) t.args.push_back(word_of(a, r.buffers[0]));
        }
        if (task_launches.empty()) t.launches.push_back({0, 0, 0, 0});  // counts as done, runs nothing
        slot.launch_count = launch_count(task);
        slot.publish = static_cast<int>(task) == options.never_publish ? 0 : 1;
        t.slots.push_back(slot);
      }
      t.svm_slots = upload(t.slots);
      t.svm_launches = upload(t.launches);
      t.svm_waits = upload(t.waits);
      t.svm_args = upload(t.args);
    }
    reset_counters();
    have_record = false;
  }

  void start(int count, bool record) {
    if (broken) throw runtime_error("fused executor: a wait failed before; the run cannot continue");
    finish();
    if (count <= 0) return;
    if (epoch + count > kEpochLimit) reset_counters();
    const int epoch0 = static_cast<int>(epoch + 1);
    {
      const std::lock_guard<std::mutex> lock(completion.mutex);
      completion.pending = 0;
    }
    in_flight_device.clear();
    for (std::size_t d = 0; d < tables.size(); ++d) {
      DeviceTables& t = tables[d];
      if (t.tasks.empty()) continue;
      const cl_int slot_count = static_cast<cl_int>(t.slots.size());
      const cl_int device = static_cast<cl_int>(d), substeps = count, rec = record ? 1 : 0, stride = stamp_stride;
      cl_uint i = 0;
      auto set_svm = [&](void* p) {
        check_cl(clSetKernelArgSVMPointer(t.kernel(), i++, p), "setting a dispatcher argument");
      };
      auto set_int = [&](cl_int v) {
        check_cl(clSetKernelArg(t.kernel(), i++, sizeof v, &v), "setting a dispatcher argument");
      };
      set_svm(t.svm_slots);
      set_int(slot_count);
      set_svm(t.svm_launches);
      set_svm(t.svm_waits);
      set_svm(t.svm_args);
      set_svm(counters);
      set_svm(control);
      set_svm(stamps);
      set_int(stride);
      set_int(device);
      set_int(epoch0);
      set_int(substeps);
      set_int(rec);
      const std::size_t global = static_cast<std::size_t>(groups[d]), local = 1;
      cl_event e = nullptr;
      check_cl(clEnqueueNDRangeKernel(r.set.queues[d](), t.kernel(), 1, nullptr, &global, &local, 0, nullptr, &e),
               "enqueueing a dispatcher");
      {
        const std::lock_guard<std::mutex> lock(completion.mutex);
        ++completion.pending;
      }
      check_cl(clSetEventCallback(e, CL_COMPLETE, on_complete, &completion), "watching a dispatcher");
      in_flight.push_back(e);
      in_flight_device.push_back(static_cast<sched::DeviceId>(d));
    }
    for (std::size_t d : in_flight_device) check_cl(clFlush(r.set.queues[d]()), "flushing a queue");
    epoch += count;
    last_substeps = count;
    if (record) have_record = true;
  }

  long long progress() const {
    long long sum = 0;
    for (std::size_t d = 0; d < r.set.devices.size(); ++d) sum += load(control + ATS_LINE * (1 + d));
    return sum;
  }

  std::string stall_message() const {
    std::string what;
    for (std::size_t d = 0; d < r.set.devices.size(); ++d) {
      int* mine = control + ATS_LINE * (1 + d);
      if (load(mine + 1) == 0) continue;
      const auto& g = r.plan.graph;
      const int task = mine[2], waited = mine[3];
      const std::size_t producer = device_of.at(waited);
      what += fmt::format("{}device {} ({}) waited for task '{}' on device {} before '{}'", what.empty() ? "" : "; ", d,
                          r.set.infos[d].name, g.task(waited).name, producer, g.task(task).name);
    }
    if (what.empty()) what = "no device reported which wait";
    return what;
  }

  void finish() {
    if (in_flight.empty()) return;
    const bool completed =
        wait_watched(in_flight, completion, control, options.wait_timeout_s, [this] { return progress(); });
    last_launches.clear();
    std::string failed;
    for (std::size_t k = 0; k < in_flight.size(); ++k) {
      cl_int status = CL_COMPLETE;
      clGetEventInfo(in_flight[k], CL_EVENT_COMMAND_EXECUTION_STATUS, sizeof status, &status, nullptr);
      if (status < 0) failed = fmt::format("device {}: {}", in_flight_device[k], cl_error_name(status));
      cl_ulong a = 0, b = 0;
      clGetEventProfilingInfo(in_flight[k], CL_PROFILING_COMMAND_START, sizeof a, &a, nullptr);
      clGetEventProfilingInfo(in_flight[k], CL_PROFILING_COMMAND_END, sizeof b, &b, nullptr);
      last_launches.push_back(
          {in_flight_device[k], last_substeps, (static_cast<double>(b) - static_cast<double>(a)) * 1e-6});
      clReleaseEvent(in_flight[k]);
    }
    in_flight.clear();
    if (!completed) {
      broken = true;
      throw runtime_error(
          fmt::format("fused executor: no task finished on any device for {}: {}; a device "
                      "failed or the devices do not run at the same time (try --executor events)",
                      limit_text(options.wait_timeout_s), stall_message()));
    }
    if (!failed.empty()) {
      broken = true;
      throw runtime_error(fmt::format("fused executor: a dispatcher launch failed ({})", failed));
    }
  }

  std::vector<sched::TaskTiming> timings() {
    if (!have_record) throw internal_error("executor: no substep was recorded");
    finish();
    if (clocks.empty()) return {};
    std::vector<sched::TaskTiming> out;
    double origin = std::numeric_limits<double>::infinity();
    for (std::size_t d = 0; d < tables.size(); ++d) {
      for (sched::TaskId t : tables[d].tasks) {
        double start = std::numeric_limits<double>::infinity(), end = 0.0;
        for (int g = 0; g < groups[d]; ++g) {
          const std::size_t at = 2 * (static_cast<std::size_t>(stamp_stride) * t + g);
          start = std::min(start, clocks[d].to_ms(static_cast<double>(stamps[at])));
          end = std::max(end, clocks[d].to_ms(static_cast<double>(stamps[at + 1])));
        }
        origin = std::min(origin, start);
        out.push_back({t, static_cast<sched::DeviceId>(d), start, end});
      }
    }
    for (sched::TaskTiming& t : out) {
      t.start_ms -= origin;
      t.finish_ms -= origin;
    }
    return out;
  }
};

FusedRunner::FusedRunner(const PlanResources& resources, SvmArena& arena, const FusedOptions& options)
    : impl_(std::make_unique<Impl>(resources, arena, options)) {}

FusedRunner::~FusedRunner() = default;

bool FusedRunner::has_clock() const { return !impl_->clocks.empty(); }
void FusedRunner::set_steps(const std::vector<Step>& steps) { impl_->set_steps(steps); }
void FusedRunner::start(int count, bool record) { impl_->start(count, record); }
void FusedRunner::finish() { impl_->finish(); }
std::vector<sched::TaskTiming> FusedRunner::timings() { return impl_->timings(); }
std::vector<sched::LaunchTiming> FusedRunner::launches() {
  impl_->finish();
  return impl_->last_launches;
}

namespace {

// Runs `kernels[k]` on `queues[k]` (global groups[k], local 1) at once and
// waits, giving up after `timeout_s`; returns the events' (start, end) in
// ns, or nothing when it gave up.
struct ProbeRun {
  bool completed = false;
  std::vector<std::pair<double, double>> spans;
};

ProbeRun run_probe(const DeviceSet::Impl& set, const std::vector<std::size_t>& devices,
                   const std::vector<cl::Kernel>& kernels, const std::vector<std::size_t>& work_groups, int* control,
                   double timeout_s) {
  Completion completion;
  std::vector<cl_event> events;
  store(control, 0);
  for (std::size_t k = 0; k < devices.size(); ++k) {
    const std::size_t local = 1;
    cl_event e = nullptr;
    check_cl(clEnqueueNDRangeKernel(set.queues[devices[k]](), kernels[k](), 1, nullptr, &work_groups[k], &local, 0,
                                    nullptr, &e),
             "enqueueing a probe");
    {
      const std::lock_guard<std::mutex> lock(completion.mutex);
      ++completion.pending;
    }
    check_cl(clSetEventCallback(e, CL_COMPLETE, on_complete, &completion), "watching a probe");
    events.push_back(e);
  }
  for (std::size_t d : devices) check_cl(clFlush(set.queues[d]()), "flushing a queue");
  ProbeRun run;
  run.completed = wait_watched(events, completion, control, timeout_s, [] { return 0LL; });
  for (cl_event e : events) {
    cl_ulong a = 0, b = 0;
    clGetEventProfilingInfo(e, CL_PROFILING_COMMAND_START, sizeof a, &a, nullptr);
    clGetEventProfilingInfo(e, CL_PROFILING_COMMAND_END, sizeof b, &b, nullptr);
    run.spans.emplace_back(static_cast<double>(a), static_cast<double>(b));
    clReleaseEvent(e);
  }
  store(control, 0);
  return run;
}

cl::Program probe_program(const DeviceSet::Impl& set) {
  return build_program(set.contexts.at(0), set.devices, "probe", language_option(set));
}

// Ms per hop of `hops` handshakes between `from` and `to` (the fastest of
// `repetitions` rounds), or a negative value when they did not run at the
// same time.
double handshake_ms(const DeviceSet::Impl& set, SvmArena& arena, std::size_t from, std::size_t to, int hops,
                    int repetitions, double timeout_s) {
  const cl::Program program = probe_program(set);
  int* flag = static_cast<int*>(arena.allocate(sizeof(int)));
  int* control = static_cast<int*>(arena.allocate(sizeof(int)));
  std::vector<cl::Kernel> kernels;
  for (int role = 0; role < 2; ++role) {
    cl::Kernel k(program, "probe_handshake");
    const cl_int h = hops;
    check_cl(clSetKernelArgSVMPointer(k(), 0, flag), "setting a probe argument");
    check_cl(clSetKernelArg(k(), 1, sizeof(cl_int), &role), "setting a probe argument");
    check_cl(clSetKernelArg(k(), 2, sizeof(cl_int), &h), "setting a probe argument");
    check_cl(clSetKernelArgSVMPointer(k(), 3, control), "setting a probe argument");
    kernels.push_back(k);
  }
  std::vector<double> per_hop;
  bool completed = true;
  // The first round is a warm-up: a kernel's first launch loads its binary
  // inside the launch's profiled time.
  for (int rep = 0; rep <= repetitions && completed; ++rep) {
    store(flag, 0);
    const ProbeRun run = run_probe(set, {from, to}, kernels, {1, 1}, control, timeout_s);
    completed = run.completed;
    if (!completed || rep == 0) continue;
    const double overlap =
        std::min(run.spans[0].second, run.spans[1].second) - std::max(run.spans[0].first, run.spans[1].first);
    per_hop.push_back(std::max(overlap, 0.0) * 1e-6 / (2.0 * hops));
  }
  arena.release(flag);
  arena.release(control);
  if (!completed || per_hop.empty()) return -1.0;
  // The fastest round: a slower one had a partner descheduled for a timer
  // tick (measured: 10 µs per hop once in a while, against 0.04 µs).
  return *std::min_element(per_hop.begin(), per_hop.end());
}

}  // namespace

double FusedRunner::latency_ms(std::size_t from, std::size_t to, int repetitions) {
  impl_->finish();
  // Few hops: on a loaded machine a spinning partner may be descheduled, and
  // each hop then costs up to a scheduler time slice.
  const double ms = handshake_ms(impl_->r.set, impl_->arena, from, to, 200, std::clamp(repetitions / 2, 3, 10),
                                 impl_->options.wait_timeout_s);
  if (ms < 0.0) {
    throw runtime_error(
        fmt::format("fused executor: devices {} and {} did not run at the same time (an SVM "
                    "handshake between them timed out); use --executor events",
                    from, to));
  }
  return ms;
}

std::string check_concurrency(const DeviceSet::Impl& set, SvmArena& arena, double timeout_s) {
  const cl::Program program = probe_program(set);
  for (std::size_t d = 0; d < set.devices.size(); ++d) {
    const std::size_t groups = static_cast<std::size_t>(std::max(1, set.infos[d].compute_units));
    if (groups < 2) continue;
    int* counter = static_cast<int*>(arena.allocate(sizeof(int)));
    int* control = static_cast<int*>(arena.allocate(sizeof(int)));
    cl::Kernel k(program, "probe_gather");
    check_cl(clSetKernelArgSVMPointer(k(), 0, counter), "setting a probe argument");
    check_cl(clSetKernelArgSVMPointer(k(), 1, control), "setting a probe argument");
    const bool ok = run_probe(set, {d}, {k}, {groups}, control, timeout_s).completed;
    arena.release(counter);
    arena.release(control);
    if (!ok) {
      return fmt::format("device {} ({}) did not run its {} work-groups at the same time", d, set.infos[d].name,
                         groups);
    }
  }
  for (std::size_t d = 1; d < set.devices.size(); ++d) {
    if (handshake_ms(set, arena, 0, d, 64, 1, timeout_s) < 0.0) {
      return fmt::format("devices 0 ({}) and {} ({}) did not run at the same time", set.infos[0].name, d,
                         set.infos[d].name);
    }
  }
  return "";
}

}  // namespace atssim::device
