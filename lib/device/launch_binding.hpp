#pragma once
// Checks a plan's launches against the task functions its program declares
// (kernels/common/task.h) before anything runs, so a launch that names an
// unknown function or passes the wrong arguments fails loudly, naming both
// (internal to lib/device).
#include <vector>

#include "plan/element_sets.hpp"
#include "plan/substep_plan.hpp"

namespace atssim::device {

// Per task, per launch: the function's case in the program's dispatcher.
// Throws atssim::Error (runtime: a bug in the solver, not in the input).
std::vector<std::vector<int>> bind_launches(const plan::SubstepPlan& plan);

// Per task, the bytes its launches write (plan::written_ranges, with the
// writable arguments from the functions' declarations: non-const pointers).
std::vector<plan::ElementSets> written_by_task(const plan::SubstepPlan& plan,
                                               std::span<const std::size_t> buffer_bytes);

}  // namespace atssim::device
