#include "device/launch_binding.hpp"

#include <fmt/format.h>

#include "kernels/embedded_programs.hpp"
#include "util/error.hpp"

namespace atssim::device {

namespace {

char kind_letter(plan::KernelArg::Kind kind) {
  switch (kind) {
    case plan::KernelArg::Kind::buffer:
      return 'b';
    case plan::KernelArg::Kind::i32:
      return 'i';
    case plan::KernelArg::Kind::f32:
      return 'f';
  }
  return '?';
}

const char* kind_name(char letter) {
  return letter == 'b' ? "a buffer" : letter == 'i' ? "an int" : letter == 'f' ? "a float" : "?";
}

}  // namespace

std::vector<std::vector<int>> bind_launches(const plan::SubstepPlan& plan) {
  const auto tasks = kernels::program_tasks(plan.program);
  std::vector<std::vector<int>> out(plan.graph.size());
  for (sched::TaskId t = 0; t < plan.graph.size(); ++t) {
    const std::string& task = plan.graph.task(t).name;
    for (const plan::KernelLaunch& launch : plan.launches.at(t)) {
      const kernels::TaskSignature* sig = nullptr;
      for (const auto& s : tasks) {
        if (s.name == launch.function) sig = &s;
      }
      if (sig == nullptr) {
        std::string known;
        for (const auto& s : tasks) known += fmt::format("{}{}", known.empty() ? "" : ", ", s.name);
        throw internal_error(
            fmt::format("task '{}' launches '{}', which program '{}' does not declare "
                        "as a task function (it has: {})",
                        task, launch.function, plan.program, known.empty() ? "none" : known));
      }
      if (launch.args.size() != sig->kinds.size()) {
        throw internal_error(fmt::format("task '{}' passes {} arguments to {}({}), which takes {}", task,
                                         launch.args.size(), sig->name, sig->parameters, sig->kinds.size()));
      }
      for (std::size_t a = 0; a < launch.args.size(); ++a) {
        const plan::KernelArg& arg = launch.args[a];
        if (kind_letter(arg.kind) != sig->kinds[a]) {
          throw internal_error(fmt::format(
              "task '{}' passes {} as argument {} of {}({}), which "
              "expects {}",
              task, kind_name(kind_letter(arg.kind)), a + 1, sig->name, sig->parameters, kind_name(sig->kinds[a])));
        }
        if (arg.kind == plan::KernelArg::Kind::buffer &&
            (arg.buffer < 0 || arg.buffer >= static_cast<plan::BufferId>(plan.buffers.size()))) {
          throw internal_error(fmt::format("task '{}' passes buffer {} to {}, the plan has {}", task, arg.buffer,
                                           sig->name, plan.buffers.size()));
        }
      }
      // What a launch declares it writes must be one of the buffers it may
      // write through (the copies between memories follow the declaration).
      for (const plan::WriteSpan& w : launch.writes) {
        bool writable = false;
        for (std::size_t a = 0; a < launch.args.size(); ++a) {
          writable = writable || (launch.args[a].kind == plan::KernelArg::Kind::buffer &&
                                  launch.args[a].buffer == w.buffer && a < sig->access.size() && sig->access[a] == 'w');
        }
        if (!writable) {
          throw internal_error(
              fmt::format("task '{}' declares a write to buffer {}, which {} is not "
                          "passed as a writable argument",
                          task, w.buffer, sig->name));
        }
      }
      if (launch.range.first < 0 || launch.range.count < 0) {
        throw internal_error(fmt::format("task '{}' launches {} over [{}, +{})", task, sig->name, launch.range.first,
                                         launch.range.count));
      }
      out[t].push_back(sig->index);
    }
  }
  return out;
}

std::vector<plan::ElementSets> written_by_task(const plan::SubstepPlan& plan,
                                               std::span<const std::size_t> buffer_bytes) {
  const auto tasks = kernels::program_tasks(plan.program);
  std::vector<plan::ElementSets> out(plan.graph.size());
  for (sched::TaskId t = 0; t < plan.graph.size(); ++t) {
    for (const plan::KernelLaunch& launch : plan.launches[t]) {
      std::vector<char> writable(launch.args.size(), 1);  // an undeclared function: assume it writes everything
      for (const auto& sig : tasks) {
        if (sig.name != launch.function) continue;
        for (std::size_t a = 0; a < writable.size() && a < sig.access.size(); ++a) writable[a] = sig.access[a] == 'w';
      }
      out[t].add(plan::written_elements(launch, writable, buffer_bytes));
    }
  }
  return out;
}

}  // namespace atssim::device
