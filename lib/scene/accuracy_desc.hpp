#pragma once
// What a scene asks of `run --tolerance` / `--budget` (solver.tolerance,
// solver.budget_ms, solver.recheck, solver.methods; docs/scene-format.md):
// atssim then chooses the method, the iterations and the schedule itself.
#include <string>
#include <vector>

namespace atssim::scene {

struct AccuracyDesc {
  double tolerance = 0.0;            // relative energy error per substep wanted, 0 < y < 1; 0 = none
  double budget_ms = 0.0;            // wall time per frame allowed (ms); 0 = none
  int recheck = 30;                  // re-check the choice every this many frames; 0 = never
  std::vector<std::string> methods;  // the methods to choose from; empty = every one the scene allows
  std::string methods_where;         // "file:line" (or --methods) that listed them

  bool active() const { return tolerance > 0.0 || budget_ms > 0.0; }
};

}  // namespace atssim::scene
