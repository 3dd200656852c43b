#include "plan/task_kind.hpp"

#include <map>
#include <mutex>

#include <fmt/format.h>

#include "util/error.hpp"

namespace atssim::plan {

namespace {

// Every kind a task was made with, by label: kinds are constants of their
// declaring code, so the table only grows, to a few dozen entries.
struct KindTable {
  std::mutex mutex;
  std::map<int, KindTraits> by_label;
};

KindTable& kind_table() {
  static KindTable* table = new KindTable();  // never destroyed: tasks may be made during exit
  return *table;
}

}  // namespace

sched::Task make_task(std::string name, const TaskKind& kind, int iteration, int block) {
  const int label = kind.label();
  KindTable& table = kind_table();
  {
    const std::lock_guard<std::mutex> lock(table.mutex);
    const auto [it, added] = table.by_label.emplace(label, kind.traits());
    const KindTraits& known = it->second;
    if (!added && (known.name != kind.name() || known.gauss_seidel != kind.traits().gauss_seidel ||
                   known.serial != kind.traits().serial || known.per_particle != kind.traits().per_particle)) {
      throw internal_error(fmt::format("task kind '{}' has the label of the kind '{}' with other traits; rename one",
                                       kind.name(), known.name));
    }
  }
  return {std::move(name), label, iteration, block, -1};
}

TaskKind kind_of(const sched::Task& task) {
  KindTable& table = kind_table();
  const std::lock_guard<std::mutex> lock(table.mutex);
  const auto it = table.by_label.find(task.kind);
  if (it == table.by_label.end()) {
    throw internal_error(fmt::format("plan: task '{}' has the label {}, which is no task kind", task.name, task.kind));
  }
  return TaskKind(it->second);
}

}  // namespace atssim::plan
