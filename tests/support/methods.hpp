#pragma once
// The solver registry as tests iterate it: a test that claims "every
// method" takes the names from solver::methods(), so a method added there
// is tested too.
#include <set>
#include <string>
#include <vector>

#include "plan/substep_plan.hpp"
#include "plan/task_kind.hpp"
#include "solver/method_registry.hpp"

namespace atssim::test {

// Every method's name; with `keep`, those it accepts.
template <typename Keep>
std::vector<std::string> method_names(Keep keep) {
  std::vector<std::string> names;
  for (const solver::MethodDescription* m : solver::methods()) {
    if (keep(*m)) names.emplace_back(m->name);
  }
  return names;
}
inline std::vector<std::string> method_names() {
  return method_names([](const solver::MethodDescription&) { return true; });
}

// How many kinds of Gauss-Seidel task a plan has: async overlaps the chains
// of different kinds and keeps each kind's order (He et al. 2025 §4.1.2).
inline std::size_t gauss_seidel_kinds(const plan::SubstepPlan& plan) {
  std::set<int> kinds;
  for (const sched::Task& t : plan.graph.tasks()) {
    if (plan::traits(plan::kind_of(t)).gauss_seidel) kinds.insert(t.kind);
  }
  return kinds.size();
}

}  // namespace atssim::test
