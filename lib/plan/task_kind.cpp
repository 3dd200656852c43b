#include "plan/task_kind.hpp"

#include <array>

#include <fmt/format.h>

#include "util/error.hpp"

namespace atssim::plan {

namespace {

constexpr int kFirst = static_cast<int>(TaskKind::predict);
constexpr int kLast = static_cast<int>(TaskKind::detection);

// In enum order.
constexpr std::array<KindTraits, kLast - kFirst + 1> kTraits{{
    {"predict", false, false, true},
    {"stretch", true, false, false},
    {"bend", true, false, false},
    {"tet", true, false, false},
    {"vertex", true, false, true},
    {"jacobi", false, false, true},
    {"systems", false, false, true},
    {"main", false, false, false},
    {"stencils", false, false, false},
    {"combine", false, false, true},
    {"collision", false, true, true},
    {"copy", false, false, true},
    {"update_velocity", false, false, true},
    {"publish", false, false, true},
    {"merge", false, false, true},
    {"energy", false, false, false},
    {"friction", false, false, true},
    {"detection", false, false, false},
}};

}  // namespace

const KindTraits& traits(TaskKind kind) {
  const int k = static_cast<int>(kind);
  if (k < kFirst || k > kLast) throw Error(fmt::format("plan: task kind {} is not known", k));
  return kTraits[k - kFirst];
}

std::string_view to_string(TaskKind kind) { return traits(kind).name; }

TaskKind kind_of(const sched::Task& task) {
  if (task.kind < kFirst || task.kind > kLast) {
    throw Error(fmt::format("plan: task '{}' has the label {}, which is no task kind", task.name, task.kind));
  }
  return static_cast<TaskKind>(task.kind);
}

sched::Task make_task(std::string name, TaskKind kind, int iteration, int block) {
  return {std::move(name), static_cast<int>(kind), iteration, block, -1};
}

}  // namespace atssim::plan
