#include "device/memory_copies.hpp"

#include <algorithm>
#include <limits>

#include <fmt/format.h>

#include "device/program_builder.hpp"
#include "util/error.hpp"

namespace atssim::device {

namespace {

constexpr std::size_t kNone = std::numeric_limits<std::size_t>::max();

// The callback that carries a dependency into another context: the copy (or
// marker) it watches completed, so the user event there completes too. The
// callback holds its own reference: it may run after the queues are
// finished and the executor has released the event (measured: pocl aborts
// in clSetUserEventStatus on a freed event).
void CL_CALLBACK complete_user_event(cl_event, cl_int status, void* user) {
  const auto e = static_cast<cl_event>(user);
  clSetUserEventStatus(e, status < 0 ? status : CL_COMPLETE);
  clReleaseEvent(e);
}

double event_ns(cl_event e, cl_profiling_info what) {
  cl_ulong t = 0;
  clGetEventProfilingInfo(e, what, sizeof(t), &t, nullptr);
  return static_cast<double>(t);
}

// A user event in `context` that completes when `watched` does.
cl_event signal_in(const cl::Context& context, cl_event watched) {
  cl_int err = CL_SUCCESS;
  cl_event user = clCreateUserEvent(context(), &err);
  check_cl(err, "creating a user event");
  clRetainEvent(user);  // the callback's
  check_cl(clSetEventCallback(watched, CL_COMPLETE, complete_user_event, user), "watching a copy");
  return user;
}

}  // namespace

// One transfer's staging: per element set, its place in the host buffer and,
// for scattered elements, the index lists and packed buffers in the two
// memories with their gather/scatter kernels.
struct MemoryCopies::Staged {
  struct Part {
    std::size_t offset = 0;  // in `host`
    std::size_t bytes = 0;
    bool contiguous = true;
    std::size_t first_byte = 0;  // contiguous: where the run starts in its buffer
    void* idx_from = nullptr;    // scattered: index lists and packed elements in both memories
    void* idx_to = nullptr;
    void* packed_from = nullptr;
    void* packed_to = nullptr;
    cl::Kernel gather, scatter;
    std::size_t global = 0;
  };
  std::vector<Part> parts;
  std::vector<std::byte> host;
  cl_event signal = nullptr;  // this substep's: completes in the destination's context once copied out
  cl_event out_first = nullptr, out_last = nullptr, in_first = nullptr, in_last = nullptr;  // when recording
  const cl::Context* from_context = nullptr;
  const cl::Context* to_context = nullptr;

  ~Staged() {
    for (Part& p : parts) {
      if (p.idx_from != nullptr) clSVMFree((*from_context)(), p.idx_from);
      if (p.packed_from != nullptr) clSVMFree((*from_context)(), p.packed_from);
      if (p.idx_to != nullptr) clSVMFree((*to_context)(), p.idx_to);
      if (p.packed_to != nullptr) clSVMFree((*to_context)(), p.packed_to);
    }
  }
};

namespace {

void* svm_alloc(const cl::Context& context, std::size_t bytes) {
  void* p = clSVMAlloc(context(), CL_MEM_READ_WRITE, std::max<std::size_t>(bytes, 16), 64);
  if (p == nullptr)
    throw runtime_error(fmt::format("cannot allocate {} bytes of shared virtual memory for a copy", bytes));
  return p;
}

cl::Kernel copy_kernel(const cl::Program& program, const char* name, void* to, const void* from, void* idx, int words,
                       int count) {
  cl::Kernel k(program, name);
  check_cl(clSetKernelArgSVMPointer(k(), 0, to), "setting a copy kernel's argument");
  check_cl(clSetKernelArgSVMPointer(k(), 1, from), "setting a copy kernel's argument");
  check_cl(clSetKernelArgSVMPointer(k(), 2, idx), "setting a copy kernel's argument");
  check_cl(clSetKernelArg(k(), 3, sizeof(int), &words), "setting a copy kernel's argument");
  check_cl(clSetKernelArg(k(), 4, sizeof(int), &count), "setting a copy kernel's argument");
  return k;
}

}  // namespace

MemoryCopies::MemoryCopies(const PlanResources& resources, const std::vector<Step>& steps)
    : r_(resources), steps_(steps) {
  const std::size_t devices = r_.set.devices.size();
  transfers_ = plan::plan_transfers(steps_, r_.written, devices);
  for (std::size_t m = 0; m < r_.set.contexts.size(); ++m) {
    copy_programs_.push_back(build_program(r_.set.contexts[m], r_.set.devices_of(m), "copy"));
  }
  in_at_.resize(steps_.size());
  out_at_.resize(steps_.size());
  std::vector<std::size_t> step_of(r_.plan.graph.size(), kNone);
  last_step_.assign(devices, kNone);
  for (std::size_t s = 0; s < steps_.size(); ++s) {
    step_of[steps_[s].task] = s;
    last_step_[steps_[s].device] = s;
  }
  for (std::size_t k = 0; k < transfers_.within.size(); ++k) {
    const plan::Transfer& t = transfers_.within[k];
    in_at_[t.before].push_back(k);
    out_at_[step_of.at(t.producer)].push_back(k);
    within_.push_back(stage(t));
  }
  for (const plan::Transfer& t : transfers_.boundary) boundary_.push_back(stage(t));
}

std::unique_ptr<MemoryCopies::Staged> MemoryCopies::stage(const plan::Transfer& t) {
  auto s = std::make_unique<Staged>();
  s->from_context = &r_.set.context_of(t.from);
  s->to_context = &r_.set.context_of(t.to);
  std::size_t offset = 0;
  for (const plan::ElementSet& set : t.elements.sets()) {
    Staged::Part p;
    p.offset = offset;
    p.bytes = set.bytes();
    p.contiguous = set.contiguous();
    if (p.contiguous) {
      p.first_byte = static_cast<std::size_t>(set.indices.front()) * set.element_bytes;
    } else {
      const int count = static_cast<int>(set.indices.size());
      const int words = static_cast<int>(set.element_bytes / 4);
      const std::size_t idx_bytes = set.indices.size() * sizeof(std::int32_t);
      p.idx_from = svm_alloc(*s->from_context, idx_bytes);
      p.idx_to = svm_alloc(*s->to_context, idx_bytes);
      p.packed_from = svm_alloc(*s->from_context, p.bytes);
      p.packed_to = svm_alloc(*s->to_context, p.bytes);
      check_cl(clEnqueueSVMMemcpy(r_.set.queues[t.from](), CL_TRUE, p.idx_from, set.indices.data(), idx_bytes, 0,
                                  nullptr, nullptr),
               "uploading a copy's index list");
      check_cl(clEnqueueSVMMemcpy(r_.set.queues[t.to](), CL_TRUE, p.idx_to, set.indices.data(), idx_bytes, 0, nullptr,
                                  nullptr),
               "uploading a copy's index list");
      p.gather = copy_kernel(copy_programs_[r_.set.memory_of[t.from]], "ats_gather", p.packed_from,
                             r_.buffer(t.from, set.buffer), p.idx_from, words, count);
      p.scatter = copy_kernel(copy_programs_[r_.set.memory_of[t.to]], "ats_scatter", r_.buffer(t.to, set.buffer),
                              p.packed_to, p.idx_to, words, count);
      p.global = (set.indices.size() + 63) / 64 * 64;
    }
    s->parts.push_back(std::move(p));
    offset += set.bytes();
  }
  s->host.resize(offset);
  return s;
}

MemoryCopies::~MemoryCopies() {
  for (const cl::CommandQueue& q : r_.set.queues) clFinish(q());
  for (cl_event e : graveyard_) clReleaseEvent(e);
}

void MemoryCopies::copy_out(const plan::Transfer& t, Staged& s) {
  const cl::CommandQueue& q = r_.set.queues[t.from];
  const std::size_t local = 64;
  cl_event last = nullptr;
  const auto keep = [&](cl_event e) {
    if (recording_ && s.out_first == nullptr) {
      clRetainEvent(e);
      s.out_first = e;
    }
    if (last != nullptr) graveyard_.push_back(last);
    last = e;
  };
  const auto& sets = t.elements.sets();
  for (std::size_t k = 0; k < sets.size(); ++k) {
    Staged::Part& p = s.parts[k];
    cl_event e = nullptr;
    if (p.contiguous) {
      const auto* src = static_cast<const std::byte*>(r_.buffer(t.from, sets[k].buffer)) + p.first_byte;
      check_cl(clEnqueueSVMMemcpy(q(), CL_FALSE, s.host.data() + p.offset, src, p.bytes, 0, nullptr, &e),
               "copying to the host for another device");
    } else {
      check_cl(clEnqueueNDRangeKernel(q(), p.gather(), 1, nullptr, &p.global, &local, 0, nullptr, &e),
               "gathering elements for another device");
      keep(e);
      check_cl(clEnqueueSVMMemcpy(q(), CL_FALSE, s.host.data() + p.offset, p.packed_from, p.bytes, 0, nullptr, &e),
               "copying to the host for another device");
    }
    keep(e);
  }
  if (recording_) {
    clRetainEvent(last);
    s.out_last = last;
  }
  s.signal = signal_in(r_.set.context_of(t.to), last);
  graveyard_.push_back(last);
  bytes_ += t.elements.bytes();
}

void MemoryCopies::copy_in(const plan::Transfer& t, Staged& s, std::vector<cl_event>& wait) {
  const cl::CommandQueue& q = r_.set.queues[t.to];
  const std::size_t local = 64;
  wait.push_back(s.signal);
  const auto keep = [&](cl_event e) {
    wait.clear();  // the in-order queue orders the rest
    if (recording_ && s.in_first == nullptr) {
      clRetainEvent(e);
      s.in_first = e;
    }
    if (recording_) {
      if (s.in_last != nullptr) clReleaseEvent(s.in_last);
      clRetainEvent(e);
      s.in_last = e;
    }
    graveyard_.push_back(e);
  };
  const auto& sets = t.elements.sets();
  for (std::size_t k = 0; k < sets.size(); ++k) {
    Staged::Part& p = s.parts[k];
    cl_event e = nullptr;
    void* dst = p.contiguous ? static_cast<std::byte*>(r_.buffer(t.to, sets[k].buffer)) + p.first_byte : p.packed_to;
    check_cl(clEnqueueSVMMemcpy(q(), CL_FALSE, dst, s.host.data() + p.offset, p.bytes,
                                static_cast<cl_uint>(wait.size()), wait.empty() ? nullptr : wait.data(), &e),
             "copying from the host for another device");
    keep(e);
    if (!p.contiguous) {
      check_cl(clEnqueueNDRangeKernel(q(), p.scatter(), 1, nullptr, &p.global, &local, 0, nullptr, &e),
               "scattering elements from another device");
      keep(e);
    }
  }
  graveyard_.push_back(s.signal);
  s.signal = nullptr;
}

void MemoryCopies::before_step(std::size_t s, std::vector<cl_event>& wait) {
  for (std::size_t k : in_at_.at(s)) copy_in(transfers_.within[k], *within_[k], wait);
}

void MemoryCopies::after_step(std::size_t s) {
  for (std::size_t k : out_at_.at(s)) copy_out(transfers_.within[k], *within_[k]);
}

std::vector<std::vector<cl_event>> MemoryCopies::end_substep() {
  const std::size_t devices = r_.set.devices.size();
  for (std::size_t k = 0; k < transfers_.boundary.size(); ++k) copy_out(transfers_.boundary[k], *boundary_[k]);
  for (std::size_t k = 0; k < transfers_.boundary.size(); ++k) {
    std::vector<cl_event> none;
    copy_in(transfers_.boundary[k], *boundary_[k], none);
  }
  std::vector<std::vector<cl_event>> next(devices);
  for (std::size_t d = 0; d < devices; ++d) {
    if (last_step_[d] == kNone) continue;
    cl_event end = nullptr;
    check_cl(clEnqueueMarkerWithWaitList(r_.set.queues[d](), 0, nullptr, &end), "marking the end of a substep");
    for (std::size_t x = 0; x < devices; ++x) {
      if (x == d || last_step_[x] == kNone) continue;
      cl_event b = signal_in(r_.set.context_of(x), end);
      next[x].push_back(b);
      graveyard_.push_back(b);
    }
    graveyard_.push_back(end);
  }
  for (const cl::CommandQueue& q : r_.set.queues) check_cl(clFlush(q()), "flushing a queue");
  recording_ = false;
  return next;
}

std::size_t MemoryCopies::take_bytes() {
  const std::size_t b = bytes_;
  bytes_ = 0;
  return b;
}

std::vector<sched::CopyTiming> MemoryCopies::recorded() {
  std::vector<sched::CopyTiming> out;
  const auto take = [&](const plan::Transfer& t, Staged& s) {
    if (s.out_first == nullptr || s.in_last == nullptr) return;
    const double ms =
        (event_ns(s.out_last, CL_PROFILING_COMMAND_END) - event_ns(s.out_first, CL_PROFILING_COMMAND_START) +
         event_ns(s.in_last, CL_PROFILING_COMMAND_END) - event_ns(s.in_first, CL_PROFILING_COMMAND_START)) *
        1e-6;
    out.push_back({static_cast<sched::DeviceId>(t.from), static_cast<sched::DeviceId>(t.to), t.elements.bytes(), ms});
    for (cl_event* e : {&s.out_first, &s.out_last, &s.in_first, &s.in_last}) {
      clReleaseEvent(*e);
      *e = nullptr;
    }
  };
  for (const cl::CommandQueue& q : r_.set.queues) check_cl(clFinish(q()), "waiting for a device");
  for (std::size_t k = 0; k < within_.size(); ++k) take(transfers_.within[k], *within_[k]);
  for (std::size_t k = 0; k < boundary_.size(); ++k) take(transfers_.boundary[k], *boundary_[k]);
  return out;
}

LinkMeasurement measure_link(const PlanResources& r, std::size_t from, std::size_t to, int repetitions) {
  const std::size_t small = 64, large = std::size_t(4) << 20;
  const auto alloc = [&](std::size_t device) {
    void* p = clSVMAlloc(r.set.context_of(device)(), CL_MEM_READ_WRITE, large, 64);
    if (p == nullptr) throw runtime_error("cannot allocate shared virtual memory for the link probe");
    return p;
  };
  void* src = alloc(from);
  void* dst = alloc(to);
  std::vector<std::byte> host(large);
  const auto once = [&](std::size_t bytes) {
    cl_event out = nullptr, in = nullptr;
    check_cl(clEnqueueSVMMemcpy(r.set.queues[from](), CL_FALSE, host.data(), src, bytes, 0, nullptr, &out),
             "probing a link");
    cl_event user = signal_in(r.set.context_of(to), out);
    check_cl(clEnqueueSVMMemcpy(r.set.queues[to](), CL_FALSE, dst, host.data(), bytes, 1, &user, &in),
             "probing a link");
    check_cl(clFlush(r.set.queues[from]()), "flushing a queue");
    check_cl(clFinish(r.set.queues[to]()), "waiting for the link probe");
    check_cl(clFinish(r.set.queues[from]()), "waiting for the link probe");
    const double ms = (event_ns(in, CL_PROFILING_COMMAND_END) - event_ns(out, CL_PROFILING_COMMAND_START)) * 1e-6;
    for (cl_event e : {out, in, user}) clReleaseEvent(e);
    return std::max(ms, 0.0);
  };
  const auto median = [&](std::size_t bytes) {
    std::vector<double> ms;
    for (int k = 0; k <= repetitions; ++k) {
      const double t = once(bytes);
      if (k > 0) ms.push_back(t);  // the first pays for first use
    }
    std::nth_element(ms.begin(), ms.begin() + ms.size() / 2, ms.end());
    return ms[ms.size() / 2];
  };
  const double a = median(small), b = median(large);
  clSVMFree(r.set.context_of(from)(), src);
  clSVMFree(r.set.context_of(to)(), dst);
  return {std::max(a, 1e-6), std::max(b - a, 1e-9) / static_cast<double>(large - small)};
}

}  // namespace atssim::device
