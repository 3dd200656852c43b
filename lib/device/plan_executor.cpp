#include "device/plan_executor.hpp"

#include <algorithm>
#include <chrono>
#include <map>
#include <mutex>
#include <numeric>

#include <fmt/format.h>

#include "device/cycle_clock.hpp"
#include "device/event_runner.hpp"
#include "device/fused_runner.hpp"
#include "device/launch_binding.hpp"
#include "device/memory_copies.hpp"
#include "device/program_builder.hpp"
#include "device/svm_arena.hpp"
#include "plan/split_plan.hpp"
#include "util/error.hpp"

namespace atssim::device {

std::string language_option(const DeviceSet::Impl& set) {
  const bool all_3 = std::all_of(set.infos.begin(), set.infos.end(),
                                 [](const DeviceInfo& d) { return d.c_version.find("3.0") != std::string::npos; });
  if (all_3) return "-cl-std=CL3.0";
  const bool all_2 = std::all_of(set.infos.begin(), set.infos.end(), [](const DeviceInfo& d) {
    return d.c_version.find("2.") != std::string::npos || d.c_version.find("3.") != std::string::npos;
  });
  return all_2 ? "-cl-std=CL2.0" : "-cl-std=CL1.2";
}

namespace {

bool use_fine_grain(const DeviceSet& devices, const ExecutorOptions& o, ExecutorKind kind) {
  if (kind == ExecutorKind::fused) return true;
  return o.svm == SvmMode::fine || (o.svm == SvmMode::automatic && devices.fine_grain_svm());
}

// Whether the devices run the dispatcher's waits: probed once per set. The
// probe's own limit is not the run's wait timeout (a short one would fail
// the probe on a loaded machine, where a spinning partner is descheduled for
// whole time slices); it is only paid where the devices really cannot meet.
const std::string& concurrency_problem(const DeviceSet::Impl& set, SvmArena& arena) {
  constexpr double probe_timeout_s = 2.0;
  static auto* cache = new std::map<const DeviceSet::Impl*, std::string>();
  static std::mutex mutex;
  const std::lock_guard<std::mutex> lock(mutex);
  auto it = cache->find(&set);
  if (it == cache->end()) it = cache->emplace(&set, check_concurrency(set, arena, probe_timeout_s)).first;
  return it->second;
}

}  // namespace

struct PlanExecutor::Impl {
  const DeviceSet::Impl& set;
  plan::SubstepPlan plan;
  ExecutorOptions options;
  ExecutorKind kind;
  std::vector<std::unique_ptr<SvmArena>> arenas;  // per memory: the plan's buffers
  SvmArena sync_arena;                            // fused: counters and records (fine grain, atomics)
  PlanResources resources;
  // The cache_state and carried buffers, with their initial contents.
  std::vector<std::pair<plan::BufferId, std::vector<std::byte>>> cache_states, carried;
  std::vector<Step> steps;
  std::unique_ptr<EventRunner> events;  // created when first needed
  std::unique_ptr<FusedRunner> fused;
  std::vector<sched::TaskId> topological;

  Impl(const DeviceSet& devices, plan::SubstepPlan p, const ExecutorOptions& o)
      : set(devices.impl()),
        plan(std::move(p)),
        options(o),
        kind(choose_executor(o.kind, devices.infos(), devices.memories())),
        sync_arena(devices.impl().contexts.at(0), true, true),
        resources{devices.impl(), plan, {}, {}, {}, {}, {}} {
    if (options.device >= set.devices.size()) {
      throw internal_error(
          fmt::format("executor: device {} is not in the set of {}", options.device, set.devices.size()));
    }
    const bool fine = use_fine_grain(devices, o, kind);
    if (fine && !devices.fine_grain_svm()) {
      throw input_error("fine-grain SVM was asked for but a device does not offer it; use --svm coarse");
    }
    for (const cl::Context& c : set.contexts) arenas.push_back(std::make_unique<SvmArena>(c, fine));
    resources.functions = bind_launches(plan);
    if (kind == ExecutorKind::fused) {
      const std::string& problem = concurrency_problem(set, sync_arena);
      if (!problem.empty()) {
        if (options.kind == ExecutorKind::fused) {
          throw runtime_error(fmt::format("executor 'fused' cannot run here: {}; use --executor events", problem));
        }
        kind = ExecutorKind::events;
      }
    }
    resources.buffers.resize(set.contexts.size());
    for (auto& spec : plan.buffers) {
      for (std::size_t m = 0; m < set.contexts.size(); ++m) {
        void* ptr = arenas[m]->allocate(spec.initial.size());
        arenas[m]->write(set.queues[first_device_of(m)], ptr, spec.initial.data(), spec.initial.size());
        resources.buffers[m].push_back(ptr);
      }
      resources.sizes.push_back(spec.initial.size());
      const auto id = static_cast<plan::BufferId>(resources.sizes.size() - 1);
      if (spec.role == plan::BufferRole::cache_state) cache_states.emplace_back(id, spec.initial);
      if (spec.role == plan::BufferRole::carried) carried.emplace_back(id, spec.initial);
      std::vector<std::byte>().swap(spec.initial);  // the devices hold it now
    }
    resources.written = written_by_task(plan, resources.sizes);
    plan::weigh_edges_by_writes(plan.graph, resources.written);
    const bool clock = kind == ExecutorKind::fused && options.task_clock && !cycle_clocks(set, sync_arena).empty();
    for (std::size_t m = 0; m < set.contexts.size(); ++m) {
      resources.programs.push_back(
          build_program(set.contexts[m], set.devices_of(m), plan.program,
                        fmt::format("{} -DATS_FUSED={} -DATS_TASK_CLOCK={}", language_option(set),
                                    kind == ExecutorKind::fused ? 1 : 0, clock ? 1 : 0)));
    }
    if (kind == ExecutorKind::fused) {
      fused = std::make_unique<FusedRunner>(resources, sync_arena,
                                            FusedOptions{options.wait_timeout_s, clock, options.never_publish});
    } else {
      events = std::make_unique<EventRunner>(resources, options.local_size);
    }
    topological = plan.graph.topological_order();
  }

  std::size_t first_device_of(std::size_t memory) const {
    for (std::size_t d = 0; d < set.devices.size(); ++d) {
      if (set.memory_of[d] == memory) return d;
    }
    return 0;
  }

  EventRunner& event_runner() {
    if (!events) {
      events = std::make_unique<EventRunner>(resources, options.local_size);
      events->set_steps(steps);
    }
    return *events;
  }

  void set_steps(std::vector<Step> new_steps) {
    // A refit that kept the schedule (the usual frame) changes nothing.
    if (new_steps == steps && !steps.empty()) return;
    steps = std::move(new_steps);
    if (fused) fused->set_steps(steps);
    if (events) events->set_steps(steps);
  }

  void finish() {
    if (fused) fused->finish();
    if (events) events->finish();
  }

  void run(int count, bool record) {
    if (fused) {
      fused->start(count, record);
    } else {
      events->enqueue(count, record);
    }
  }

  std::vector<sched::TaskTiming> recorded() { return fused ? fused->timings() : events->timings(); }

  // Runs `substeps` substeps on each device alone and reports each one's
  // timings; what they cost is the observer's to decide.
  void profile(int substeps, sched::TimingObserver& observer, int min_substeps, double budget_ms) {
    plan::PlanState snapshot;
    read_state(snapshot);
    const std::vector<Step> kept = steps;
    // Fused without a task clock: per-task events, whose launch gap the
    // observer is told about.
    const bool by_events = fused && !fused->has_clock();
    for (std::size_t d = 0; d < set.devices.size(); ++d) {
      const auto device = static_cast<sched::DeviceId>(d);
      set_steps(all_on(d));
      const auto start = std::chrono::steady_clock::now();
      for (int r = 0; r < substeps; ++r) {
        const std::chrono::duration<double, std::milli> spent = std::chrono::steady_clock::now() - start;
        if (budget_ms > 0.0 && r >= min_substeps && spent.count() >= budget_ms) break;
        if (by_events) {
          event_runner().enqueue(1, true);
          observer.substep_alone(device, event_runner().timings());
        } else {
          // Two substeps, the last timed: a launch's first substep also
          // waits for its work-groups to be started.
          run(2, true);
          observer.substep_alone(device, recorded());
        }
      }
      if (by_events) observer.launch_gap(device, event_runner().launch_gap_ms(d, 10));
    }
    reset(snapshot);
    set_steps(kept);
  }

  std::vector<Step> all_on(std::size_t device) const {
    std::vector<Step> out;
    for (sched::TaskId t : topological) out.push_back({t, device, {}});
    return out;
  }

  // After finish() every memory holds the whole state (the last substep's
  // copies included): read the home device's.
  std::vector<std::byte> read(plan::BufferId id) {
    std::vector<std::byte> out;
    read_into(id, out, 0);
    return out;
  }

  // Buffer `id`'s bytes into out[at, at + size), out grown to hold them
  // (its storage kept when it already does).
  void read_into(plan::BufferId id, std::vector<std::byte>& out, std::size_t at) {
    finish();
    const std::size_t size = resources.sizes.at(id);
    if (out.size() < at + size) out.resize(at + size);
    const std::size_t m = set.memory_of[options.device];
    arenas[m]->read(set.queues[options.device], resources.buffers[m].at(id), out.data() + at, size);
  }

  void write(plan::BufferId id, std::span<const std::byte> bytes) {
    finish();
    if (bytes.size() != resources.sizes.at(id)) throw internal_error("executor: write of the wrong size");
    for (std::size_t m = 0; m < set.contexts.size(); ++m) {
      arenas[m]->write(set.queues[first_device_of(m)], resources.buffers[m].at(id), bytes.data(), bytes.size());
    }
  }

  // Into `state`'s storage where it has the sizes already (a frame's state
  // read into the last one's: no fresh pages for a large carried state).
  void read_state(plan::PlanState& state) {
    // Sized exactly first (a no-op for the last frame's state: clearing
    // and growing it would zero every byte again).
    const plan::BufferId x = plan.buffer(plan::BufferRole::positions);
    state.positions.resize(resources.sizes.at(x));
    read_into(x, state.positions, 0);
    const plan::BufferId v = plan.find_buffer(plan::BufferRole::velocities);
    state.velocities.resize(v >= 0 ? resources.sizes.at(v) : 0);
    if (v >= 0) read_into(v, state.velocities, 0);
    state.carried.resize(carried_bytes());
    std::size_t at = 0;
    for (const auto& [id, initial] : carried) {
      read_into(id, state.carried, at);
      at += initial.size();
    }
  }

  std::size_t carried_bytes() const {
    std::size_t bytes = 0;
    for (const auto& [id, initial] : carried) bytes += initial.size();
    return bytes;
  }

  void reset(const plan::PlanState& state) {
    write(plan.buffer(plan::BufferRole::positions), state.positions);
    if (const plan::BufferId v = plan.find_buffer(plan::BufferRole::velocities); v >= 0) write(v, state.velocities);
    if (!state.carried.empty() && state.carried.size() != carried_bytes()) {
      throw internal_error(
          fmt::format("executor: a state carries {} bytes, the plan {}", state.carried.size(), carried_bytes()));
    }
    std::size_t at = 0;
    for (const auto& [id, initial] : carried) {
      if (state.carried.empty()) {
        write(id, initial);
      } else {
        write(id, std::span(state.carried).subspan(at, initial.size()));
        at += initial.size();
      }
    }
    for (const auto& [id, initial] : cache_states) write(id, initial);
  }
};

PlanExecutor::PlanExecutor(const DeviceSet& devices, plan::SubstepPlan plan, ExecutorOptions options)
    : impl_(std::make_unique<Impl>(devices, std::move(plan), options)) {
  run_on(options.device);
}

PlanExecutor::~PlanExecutor() = default;

const plan::SubstepPlan& PlanExecutor::plan() const { return impl_->plan; }
ExecutorKind PlanExecutor::kind() const { return impl_->kind; }
std::size_t PlanExecutor::device_count() const { return impl_->set.devices.size(); }
bool PlanExecutor::has_task_clock() const { return impl_->fused && impl_->fused->has_clock(); }
std::size_t PlanExecutor::work_group_elements() const { return impl_->fused ? 0 : impl_->options.local_size; }

void PlanExecutor::run_on(std::size_t device) {
  if (device >= device_count()) throw internal_error(fmt::format("executor: no device {}", device));
  impl_->set_steps(impl_->all_on(device));
}

void PlanExecutor::run_schedule(const sched::Schedule& schedule, std::span<const sched::Wait> waits) {
  const auto& graph = impl_->plan.graph;
  if (schedule.task_count() != graph.size() || schedule.devices.size() > device_count()) {
    throw internal_error(
        fmt::format("executor: a schedule of {} tasks on {} devices does not fit a plan of {} tasks on {}",
                    schedule.task_count(), schedule.devices.size(), graph.size(), device_count()));
  }
  // Start in order of predicted start, so a producer always starts before a
  // consumer that waits for it (its start is at least the producer's finish).
  std::vector<Step> steps;
  for (std::size_t d = 0; d < schedule.devices.size(); ++d) {
    for (const sched::Slot& slot : schedule.devices[d]) steps.push_back({slot.task, d, {}});
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
  for (const sched::Wait& w : waits) steps[position[w.consumer]].waits.push_back(w.producer);
  impl_->set_steps(std::move(steps));
}

std::vector<double> PlanExecutor::recut(std::span<const double> fractions, std::size_t granule) {
  auto& impl = *impl_;
  impl.finish();
  std::vector<double> shares = plan::recut_plan(impl.plan, fractions, granule);
  impl.resources.written = written_by_task(impl.plan, impl.resources.sizes);
  // The ranges live in the dispatcher tables and in the events kernels' arguments.
  if (impl.fused) impl.fused->set_steps(impl.steps);
  if (impl.events) {
    impl.events = std::make_unique<EventRunner>(impl.resources, impl.options.local_size);
    impl.events->set_steps(impl.steps);
  }
  return shares;
}

void PlanExecutor::run_substeps(int count, bool record) { impl_->run(count, record); }

std::vector<sched::TaskTiming> PlanExecutor::recorded() { return impl_->recorded(); }

std::vector<sched::LaunchTiming> PlanExecutor::launches() {
  return impl_->fused ? impl_->fused->launches() : std::vector<sched::LaunchTiming>{};
}

void PlanExecutor::profile(int substeps, sched::TimingObserver& observer, int min_substeps, double budget_ms) {
  impl_->profile(substeps, observer, min_substeps, budget_ms);
}

double PlanExecutor::measure_latency_ms(std::size_t from, std::size_t to, int repetitions) {
  impl_->finish();
  if (impl_->fused) return impl_->fused->latency_ms(from, to, repetitions);
  return impl_->event_runner().latency_ms(from, to, repetitions);
}

void PlanExecutor::finish() { impl_->finish(); }

plan::PlanState PlanExecutor::read_state() {
  plan::PlanState state;
  impl_->read_state(state);
  return state;
}
void PlanExecutor::read_state(plan::PlanState& into) { impl_->read_state(into); }
void PlanExecutor::reset(const plan::PlanState& state) { impl_->reset(state); }
std::size_t PlanExecutor::carried_bytes() const { return impl_->carried_bytes(); }
std::vector<std::byte> PlanExecutor::read(plan::BufferId id) { return impl_->read(id); }
void PlanExecutor::write(plan::BufferId id, std::span<const std::byte> bytes) { impl_->write(id, bytes); }

void PlanExecutor::read_positions(std::vector<float>& xyz) {
  const std::vector<std::byte> raw = read(impl_->plan.buffer(plan::BufferRole::positions));
  const auto* p = reinterpret_cast<const float*>(raw.data());
  const std::size_t n = raw.size() / (4 * sizeof(float));
  xyz.resize(3 * n);
  for (std::size_t i = 0; i < n; ++i) {
    xyz[3 * i] = p[4 * i];
    xyz[3 * i + 1] = p[4 * i + 1];
    xyz[3 * i + 2] = p[4 * i + 2];
  }
}

bool PlanExecutor::fine_grain() const { return impl_->arenas.front()->fine_grain(); }

std::size_t PlanExecutor::take_bytes_moved() { return impl_->events ? impl_->events->take_bytes_moved() : 0; }

std::vector<sched::CopyTiming> PlanExecutor::copies() {
  return impl_->events ? impl_->events->copies() : std::vector<sched::CopyTiming>{};
}

const plan::TransferPlan* PlanExecutor::transfer_plan() const {
  return impl_->events ? impl_->events->transfer_plan() : nullptr;
}

PlanExecutor::Link PlanExecutor::measure_link(std::size_t from, std::size_t to, int repetitions) {
  impl_->finish();
  if (impl_->set.memory_of[from] == impl_->set.memory_of[to])
    return {measure_latency_ms(from, to, 2 * repetitions), 0.0};
  const LinkMeasurement m = device::measure_link(impl_->resources, from, to, repetitions);
  return {m.latency_ms, m.ms_per_byte};
}

std::size_t PlanExecutor::memories() const { return impl_->set.contexts.size(); }

}  // namespace atssim::device
