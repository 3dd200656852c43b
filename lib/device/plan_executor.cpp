#include "device/plan_executor.hpp"

#include <fmt/format.h>

#include "device/device_set_impl.hpp"
#include "device/program_builder.hpp"
#include "device/svm_arena.hpp"
#include "util/error.hpp"

namespace atssim::device {

namespace {

struct PreparedLaunch {
  cl::Kernel kernel;
  std::size_t global = 0;
};

}  // namespace

struct PlanExecutor::Impl {
  const DeviceSet::Impl& set;
  const solver::SubstepPlan& plan;
  ExecutorOptions options;
  SvmArena arena;
  std::vector<void*> buffers;
  std::vector<std::size_t> sizes;
  std::vector<PreparedLaunch> sequence;  // launches of one substep, in task order
  cl::CommandQueue queue;

  Impl(const DeviceSet& devices, const solver::SubstepPlan& p, ExecutorOptions o)
      : set(devices.impl()),
        plan(p),
        options(o),
        arena(devices.impl().context, o.svm == SvmMode::fine ||
                                          (o.svm == SvmMode::automatic && devices.fine_grain_svm())) {
    if (options.device >= set.devices.size()) {
      throw Error(fmt::format("executor: device {} is not in the set of {}", options.device, set.devices.size()));
    }
    if (arena.fine_grain() && !devices.info(options.device).svm.fine_buffer) {
      throw input_error("fine-grain SVM was asked for but the device does not offer it; use coarse");
    }
    queue = set.queues[options.device];
    for (const auto& spec : plan.buffers) {
      void* p = arena.allocate(spec.initial.size());
      arena.write(queue, p, spec.initial.data(), spec.initial.size());
      buffers.push_back(p);
      sizes.push_back(spec.initial.size());
    }
    const cl::Program program = build_program(set.context, set.devices, plan.program);
    for (sched::TaskId id : plan.graph.topological_order()) {
      for (const solver::KernelLaunch& launch : plan.launches.at(id)) {
        if (launch.global_size == 0) continue;
        sequence.push_back(prepare(program, launch));
      }
    }
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
};

PlanExecutor::PlanExecutor(const DeviceSet& devices, const solver::SubstepPlan& plan, ExecutorOptions options)
    : impl_(std::make_unique<Impl>(devices, plan, options)) {}

PlanExecutor::~PlanExecutor() {
  if (impl_) clFinish(impl_->queue());
}

void PlanExecutor::enqueue_substeps(int count) {
  const std::size_t local = impl_->options.local_size;
  for (int s = 0; s < count; ++s) {
    for (const PreparedLaunch& l : impl_->sequence) {
      check_cl(clEnqueueNDRangeKernel(impl_->queue(), l.kernel(), 1, nullptr, &l.global, &local, 0, nullptr, nullptr),
               "enqueueing a kernel");
    }
  }
  check_cl(clFlush(impl_->queue()), "flushing the queue");
}

void PlanExecutor::finish() { check_cl(clFinish(impl_->queue()), "waiting for the device"); }

std::vector<std::byte> PlanExecutor::read(solver::BufferId id) {
  std::vector<std::byte> out(impl_->sizes.at(id));
  impl_->arena.read(impl_->queue, impl_->buffers.at(id), out.data(), out.size());
  return out;
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
